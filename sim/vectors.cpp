// `cdsim vectors`: what the scoreboard checks, written down for a bench of the
// user's own. For each triangle of the source the C++ model runs, as it does
// for `cdsim regress`, and its expectations of each block go into $readmemh
// files, one word a line, the fields of a word in the order of its layout
// (most significant first, '_' between fields):
//   triangles.hex     the stimulus: the triangle at the unit's input, and the
//                     design bits (kind_i, segment_log2_i, ...) that choose its datapath
//   setups.hex        the setup engine's results, one per triangle
//   table_writes.hex  every write of the table fill, in order
//   fragments.hex     every fragment the datapath emits, in order
//   records.hex       each triangle's record, with how many writes and fragments it has
// with vectors.svh (the counts, the unit's parameters, the words as packed
// structs), cd_widths.svh (the
// widths) and manifest.json (widths, designs, source, seed, build, layouts).
// tests/vectors/cd_scan_vectors_tb.sv replays them (docs/vectors.md).
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <stdexcept>
#include <tuple>

#include "cache_files.hpp"
#include "derived_widths.hpp"
#include "encodings.hpp"
#include "interrupt.hpp"
#include "regress.hpp"
#include "report.hpp"
#include "scan_unit.hpp"

namespace cdsim::rtl {

namespace {

struct Field {
  const char* name;
  int bits;  // a multiple of 4, so that each field is whole hex digits
};
using Layout = std::vector<Field>;

// The layouts of the files, most significant field first. vectors.svh gives
// the testbench (tests/vectors/cd_scan_vectors_tb.sv) each as a packed struct
// (struct_typedef). The bits of a setup's `bits` and a table write's `flags`
// are CD_OBS_SETUP_* and CD_OBS_WRITE_* (model/encodings.def).
const Layout kTriangle = {
    {"kind", 4},  {"segment_log2", 4}, {"quadratic", 4}, {"kim_pipelined", 4}, {"density_log2", 4},
    {"correction", 4}, {"persp", 4}, {"fallback", 4}, {"viewport_width", 16}, {"viewport_height", 16},
    {"x0", 32}, {"y0", 32}, {"q0", 32}, {"u0", 32}, {"v0", 32},
    {"x1", 32}, {"y1", 32}, {"q1", 32}, {"u1", 32}, {"v1", 32},
    {"x2", 32}, {"y2", 32}, {"q2", 32}, {"u2", 32}, {"v2", 32}};
const Layout kSetup = {{"bits", encoding::OBS_SETUP_BITS}, {"g", 32}, {"box", 64}, {"lines", 64}};
const Layout kTableWrite = {{"address", 32}, {"t_u", 64}, {"t_v", 64}, {"s_u", 64},
                            {"s_v", 64},     {"eps", 64}, {"flags", encoding::OBS_WRITE_BITS}};
const Layout kFragment = {{"x", 16}, {"y", 16}, {"u", 64}, {"v", 64}, {"flags", 8}};
const Layout kRecord = {{"cycles", 64}, {"lines", 32},        {"bands", 32},    {"pixels", 32},
                        {"flags", 8},   {"table_writes", 32}, {"fragments", 32}};

// The layout as a SystemVerilog packed struct, most significant field first.
std::string struct_typedef(const Layout& layout, const std::string& name) {
  std::string text = "typedef struct packed {\n";
  for (const Field& f : layout) text += fmt::format("  logic [{}:0] {};\n", f.bits - 1, f.name);
  return text + fmt::format("}} {};\n", name);
}

int layout_bits(const Layout& layout) {
  int bits = 0;
  for (const Field& f : layout) bits += f.bits;
  return bits;
}

// One word: the values in the layout's order, each cut to its field's width
// (two's complement for negative values), as hex digits with '_' between fields.
std::string word(const Layout& layout, std::initializer_list<int64_t> values) {
  if (values.size() != layout.size())
    throw std::logic_error(fmt::format("vectors: {} values for {} fields", values.size(), layout.size()));
  std::string text;
  auto value = values.begin();
  for (const Field& field : layout) {
    const uint64_t bits = static_cast<uint64_t>(*value++);
    const uint64_t masked = field.bits >= 64 ? bits : bits & ((uint64_t{1} << field.bits) - 1);
    if (!text.empty()) text += '_';
    text += fmt::format("{:0{}x}", masked, field.bits / 4);
  }
  return text + '\n';
}

std::string triangle_word(const Job& job) {
  const DesignSelect d = design_select(*job.design);
  const auto& v = job.triangle.vertex;
  return word(kTriangle,
              {d.kind, d.segment_log2, d.quadratic, d.kim_pipelined, d.density_log2, d.correction, d.persp, d.fallback,
               job.viewport_width, job.viewport_height,
               v[0].x, v[0].y, v[0].q_float, v[0].u, v[0].v,
               v[1].x, v[1].y, v[1].q_float, v[1].u, v[1].v,
               v[2].x, v[2].y, v[2].q_float, v[2].u, v[2].v});
}

// As the observation ports show the setup (rtl/cd_scan_unit.sv): the bits
// at CD_OBS_SETUP_*, the box as four 16-bit fields at CD_OBS_BOX_*, the
// pixel lines as two 32-bit fields at CD_OBS_LINES_*.
std::string setup_word(const Setup& s) {
  const bool no_lines = s.pixel_line_lo > s.pixel_line_hi;
  const bool depth_range = (s.flags & flag::kDepthRange) != 0;
  const auto at = [](int64_t v, int lsb, int width) {
    return (static_cast<uint64_t>(v) & ((uint64_t{1} << width) - 1)) << lsb;
  };
  const uint64_t box = at(s.major_lo, encoding::OBS_BOX_MAJOR_LO, 16) |
                       at(s.major_count, encoding::OBS_BOX_MAJOR_COUNT, 16) |
                       at(s.minor_lo, encoding::OBS_BOX_MINOR_LO, 16) | at(s.minor_hi, encoding::OBS_BOX_MINOR_HI, 16);
  const uint64_t lines = at(s.pixel_line_lo, encoding::OBS_LINES_LO, 32) | at(s.pixel_line_hi, encoding::OBS_LINES_HI, 32);
  const uint64_t bits = at(s.empty, encoding::OBS_SETUP_EMPTY, 1) | at(s.x_major, encoding::OBS_SETUP_X_MAJOR, 1) |
                        at(no_lines, encoding::OBS_SETUP_NO_LINES, 1) |
                        at(depth_range, encoding::OBS_SETUP_DEPTH_RANGE, 1);
  return word(kSetup, {static_cast<int64_t>(bits), s.g, static_cast<int64_t>(box), static_cast<int64_t>(lines)});
}

// A table write's flags, at CD_OBS_WRITE_*; EPS_CHECKED marks cd-persp's
// words, whose eps the bench compares.
int64_t write_flags(const TableWrite& w, bool persp) {
  const auto at = [](bool on, int position) { return on ? int64_t{1} << position : 0; };
  return at(persp, encoding::OBS_WRITE_EPS_CHECKED) | at(w.entry.eps_saturated, encoding::OBS_WRITE_EPS_SATURATED) |
         at((w.entry.flags & flag::kDepthRange) != 0, encoding::OBS_WRITE_DEPTH_RANGE) |
         at((w.entry.flags & flag::kTableSaturated) != 0, encoding::OBS_WRITE_SATURATED);
}

nlohmann::json layout_json(const Layout& layout) {
  nlohmann::json fields = nlohmann::json::array();
  int msb = layout_bits(layout) - 1;
  for (const Field& f : layout) {
    fields.push_back({{"name", f.name}, {"msb", msb}, {"lsb", msb - f.bits + 1}});
    msb -= f.bits;
  }
  return fields;
}

std::string describe_designs(const std::vector<const Design*>& designs) {
  std::string names;
  for (const Design* d : designs) names += (names.empty() ? "" : ",") + d->name;
  return names;
}

}  // namespace

int run_vectors_command(const VectorsOptions& given) {
  try {
    const RegressOptions& o = given.source;
    Widths widths = widths_of(o.widths);
    apply_settings(widths, o.settings);
    validate(widths);
    const std::vector<const Design*> designs = designs_for(o.design);
    if (rtl_top(*designs.front()) != RtlTop::ScanUnit)
      throw std::invalid_argument(fmt::format(
          "--design {}: the vectors replay the scan unit (rtl/cd_scan_unit.sv); the adaptive design's unit "
          "(rtl/adaptive_unit.sv) is checked by cdsim regress",
          o.design));
    // The unit elaborates only the hardware of the designs in the set.
    std::vector<const Design*> present;
    for (const Design* d : designs)
      if (std::find(present.begin(), present.end(), d) == present.end()) present.push_back(d);
    const std::vector<UnitParameter> parameters = unit_parameters(present);
    const bool has_table = std::any_of(present.begin(), present.end(), [](const Design* d) {
      return d->kind == Design::Kind::ConstantDepth;
    });

    std::cout << fmt::format("vectors: seed {}\n", o.seed);
    std::string source;
    const std::vector<Job> jobs = source_jobs(o, widths, designs, source);
    create_output_folder(given.out);
    const OutputFolderLock lock(given.out);
    std::cout << fmt::format("widths: {}{} ({})\n", o.widths, o.settings.empty() ? "" : " with --set",
                             describe(widths));
    std::cout << fmt::format("design: {} ({})\n", o.design, describe_designs(present));
    std::cout.flush();

    std::string triangles, setups, writes, fragments_text, records;
    int64_t write_count = 0, fragment_count = 0, cycles = 0;
    std::map<std::tuple<std::string, int, int>, std::unique_ptr<ScanUnit>> units;
    std::vector<Fragment> fragments;
    BlockTrace trace;
    UnitSchedule schedule(widths);
    schedule.offer_after_record(true);
    for (const Job& job : jobs) {
      throw_if_interrupted();
      auto& unit = units[{job.design->name, job.viewport_width, job.viewport_height}];
      if (!unit)
        unit = std::make_unique<ScanUnit>(*job.design, widths, job.viewport_width, job.viewport_height);
      unit->trace_blocks(&trace);
      fragments.clear();
      // One stream through the unit, whose source (the vector bench) offers a
      // triangle in the cycle the last one's record is delivered.
      TriangleRecord record = unit->compute(job.triangle, &fragments);
      record.cycles = schedule.next(unit->phases()).total();
      triangles += triangle_word(job);
      setups += setup_word(trace.setup);
      for (const TableWrite& w : trace.writes)
        writes += word(kTableWrite, {w.address, w.entry.t_u, w.entry.t_v, w.entry.s_u, w.entry.s_v,
                                     w.entry.eps, write_flags(w, job.design->persp)});
      for (const Fragment& f : fragments)
        fragments_text += word(kFragment, {f.x, f.y, f.u, f.v, f.flags});
      records += word(kRecord, {record.cycles, record.lines, record.bands, record.pixels, record.flags,
                                static_cast<int64_t>(trace.writes.size()),
                                static_cast<int64_t>(fragments.size())});
      write_count += static_cast<int64_t>(trace.writes.size());
      fragment_count += static_cast<int64_t>(fragments.size());
      cycles += record.cycles;
    }

    std::string svh = fmt::format(
        "// Generated by cdsim vectors ({}): the counts of the vector files beside this one\n"
        "// and the scan unit's parameters for their designs ({}).\n"
        "`define CD_VEC_TRIANGLES {}\n`define CD_VEC_TABLE_WRITES {}\n`define CD_VEC_FRAGMENTS {}\n",
        build_id(), describe_designs(present), jobs.size(), write_count, fragment_count);
    std::string parameter_list;
    for (const UnitParameter& p : parameters)
      parameter_list += fmt::format("{}.{}({})", parameter_list.empty() ? "" : ", ", p.name, p.value);
    svh += fmt::format("`define CD_VEC_UNIT_PARAMETERS {}\n", parameter_list);
    svh += fmt::format("`define CD_VEC_HAS_TABLE {:d}\n", has_table);
    svh += "// The words of the files, most significant field first (sim/vectors.cpp's layouts).\n";
    svh += struct_typedef(kTriangle, "triangle_t") + struct_typedef(kSetup, "setup_t") +
           struct_typedef(kTableWrite, "table_write_t") + struct_typedef(kFragment, "fragment_t") +
           struct_typedef(kRecord, "record_t");

    nlohmann::json params = nlohmann::json::object();
    for (const UnitParameter& p : parameters) params[p.name] = p.value;
    params["HasObservation"] = 1;
    nlohmann::json width_values = nlohmann::json::object();
    for (const ParamInfo& p : param_table()) width_values[p.name] = widths.*(p.field);
    const auto file = [](const char* block, const char* what, int64_t words, const Layout& layout) {
      return nlohmann::json{{"block", block}, {"what", what}, {"words", words},
                            {"bits", layout_bits(layout)}, {"fields", layout_json(layout)}};
    };
    const nlohmann::json manifest = {
        {"kind", "cdsim vectors"},
        {"build", build_id()},
        {"seed", o.seed},
        {"source", source},
        {"design", o.design},
        {"designs", describe_designs(present)},
        {"widths", describe(widths)},
        {"width_values", width_values},
        {"unit_parameters", params},
        {"model_cycles", cycles},
        {"files",
         {{"triangles.hex", file("unit input", "stimulus: one triangle a word, with the design bits",
                                 static_cast<int64_t>(jobs.size()), kTriangle)},
          {"setups.hex",
           file("setup engine",
                "obs_setup_* in the last setup cycle: bits {depth_range, no_lines, x_major, empty}; "
                "box {major_lo, major_count, minor_lo, minor_hi}; lines {pixel_line_lo, pixel_line_hi}. "
                "Only 'empty' counts for an empty triangle, and the lines not when no_lines; g and "
                "the lines only in a unit with a table",
                static_cast<int64_t>(jobs.size()), kSetup)},
          {"table_writes.hex", file("scanline table", "obs_write_* of every table write, in order; eps; flags {eps checked (cd-persp), eps_saturated, depth_range, saturated}",
                                    write_count, kTableWrite)},
          {"fragments.hex", file("correction adder (or the design's per-pixel datapath)",
                                 "frag_* of every fragment taken, in order", fragment_count, kFragment)},
          {"records.hex", file("unit output",
                               "rec_* of each triangle; the RTL's cycles are these plus the cycles "
                               "a fragment was refused; then the triangle's write and fragment counts",
                               static_cast<int64_t>(jobs.size()), kRecord)}}},
        {"headers", {{"cd_widths.svh", "the RTL's widths (cdsim widths --sv)"},
                     {"vectors.svh", "the counts, the unit's parameters and the words' packed structs, for the testbench"}}}};

    const std::filesystem::path out = given.out;
    write_files_atomic({{out / "triangles.hex", triangles},
                        {out / "setups.hex", setups},
                        {out / "table_writes.hex", writes},
                        {out / "fragments.hex", fragments_text},
                        {out / "records.hex", records},
                        {out / "vectors.svh", svh},
                        {out / "cd_widths.svh", rtl_header(widths, "vectors")},
                        {out / "manifest.json", manifest.dump(2) + "\n"}});
    std::cout << fmt::format(
        "{} triangles, {} table writes, {} fragments, {} model cycles\nwrote {}/: triangles.hex "
        "setups.hex table_writes.hex fragments.hex records.hex vectors.svh cd_widths.svh manifest.json\n",
        jobs.size(), write_count, fragment_count, cycles, given.out);
    return 0;
  } catch (const Interrupted&) {
    throw;
  } catch (const std::exception& e) {
    std::cerr << "cdsim vectors: error: " << e.what() << '\n';
    return 2;
  }
}

}  // namespace cdsim::rtl
