#!/usr/bin/env bash
# Usage: expect_error.sh REGEX COMMAND...
# Passes when COMMAND exits non-zero, without a crash, and its stderr matches REGEX.
regex=$1; shift
err=$("$@" 2>&1 >/dev/null); status=$?
echo "exit $status: $err"
if [ "$status" -eq 0 ]; then echo "FAIL: expected a non-zero exit"; exit 1; fi
if [ "$status" -ge 128 ]; then echo "FAIL: killed by a signal"; exit 1; fi
if ! grep -Eq -- "$regex" <<<"$err"; then echo "FAIL: message does not match /$regex/"; exit 1; fi
