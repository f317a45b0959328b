#include "render.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <vector>

#include "cache_files.hpp"
#include "cli_checks.hpp"
#include "exact.hpp"
#include "interrupt.hpp"
#include "report.hpp"

#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>
#include <stb/stb_easy_font.h>

namespace cdsim {

namespace {

using Rgb = std::array<uint8_t, 3>;

struct Image {
  int width = 0, height = 0;
  std::vector<uint8_t> pixels;  // RGB
  Image(int w, int h) : width(w), height(h), pixels(size_t(w) * size_t(h) * 3, 0) {}
  void set(int x, int y, Rgb c) {
    if (x < 0 || y < 0 || x >= width || y >= height) return;
    std::copy(c.begin(), c.end(), pixels.begin() + (ptrdiff_t(y) * width + x) * 3);
  }
  void fill(int x0, int y0, int x1, int y1, Rgb c) {
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) set(x, y, c);
  }
  // Text in stb_easy_font's quads, scaled up for legibility.
  void text(int x, int y, const std::string& s, Rgb colour, int scale = 2) {
    static char buffer[99999];
    const int quads = stb_easy_font_print(0, 0, const_cast<char*>(s.c_str()), nullptr, buffer, sizeof buffer);
    const float* v = reinterpret_cast<const float*>(buffer);
    const int width_px = stb_easy_font_width(const_cast<char*>(s.c_str()));
    fill(x - 4, y - 4, x + width_px * scale + 4, y + 12 * scale + 4, {0, 0, 0});
    for (int q = 0; q < quads; ++q) {
      const float* p = v + q * 16;  // 4 vertices of x, y, z, colour
      fill(x + int(p[0]) * scale, y + int(p[1]) * scale, x + int(p[8]) * scale, y + int(p[9]) * scale, colour);
    }
  }
  // The image as a PNG file's bytes (written with write_files_atomic).
  std::string png(const std::string& path) const {
    std::string bytes;
    const auto append = [](void* context, void* data, int size) {
      static_cast<std::string*>(context)->append(static_cast<const char*>(data), size_t(size));
    };
    if (!stbi_write_png_to_func(append, &bytes, width, height, 3, pixels.data(), width * 3))
      throw std::runtime_error(fmt::format("{}: cannot encode the PNG", path));
    return bytes;
  }
};

Rgb checker(double u, double v, int size) {
  const auto cell = static_cast<int64_t>(std::floor(u / size)) + static_cast<int64_t>(std::floor(v / size));
  return (cell & 1) ? Rgb{235, 235, 225} : Rgb{60, 70, 90};
}

// log10(error) from -4 to +2 on a dark-to-bright ramp.
Rgb heat(double error) {
  static const std::array<Rgb, 6> stops = {{{0, 0, 4}, {60, 15, 110}, {150, 40, 120}, {230, 90, 60}, {250, 190, 40}, {252, 255, 200}}};
  const double t = std::clamp((std::log10(std::max(error, 1e-12)) + 4.0) / 6.0, 0.0, 1.0) * (stops.size() - 1);
  const size_t i = std::min(size_t(t), stops.size() - 2);
  const double f = t - double(i);
  Rgb c;
  for (size_t k = 0; k < 3; ++k) c[k] = uint8_t(stops[i][k] + f * (stops[i + 1][k] - stops[i][k]));
  return c;
}

void heat_legend(Image& image) {
  const int x0 = 20, y0 = image.height - 70, w = 360;
  image.fill(x0 - 10, y0 - 40, x0 + w + 10, y0 + 50, {0, 0, 0});
  for (int i = 0; i < w; ++i) {
    const double error = std::pow(10.0, -4.0 + 6.0 * i / (w - 1));
    image.fill(x0 + i, y0, x0 + i + 1, y0 + 20, heat(error));
  }
  for (int e = -4; e <= 2; ++e) image.text(x0 + (e + 4) * (w - 1) / 6 - 8, y0 + 26, fmt::format("1e{}", e), {255, 255, 255}, 1);
  image.text(x0, y0 - 30, "error, texels: max(|du|, |dv|)", {255, 255, 255}, 1);
}

}  // namespace

CLI::App* add_render_command(CLI::App& app, RenderOptions& options) {
  CLI::App* render = app.add_subcommand(
      "render", "PNG per design: checkerboard beside the exact result, and an error heat map");
  add_common(render, options.common);
  render->add_option("--out", options.out, "output folder (created; locked while render runs)")
      ->capture_default_str();
  render->add_option("--checker", options.checker_texels, "checker square size, texels")
      ->check(cli::integer_in(1, 4096))
      ->capture_default_str();
  return render;
}

int run_render_command(const RenderOptions& options) {
  const Widths widths = widths_from(options.common);
  const PreparedScene scene = prepared_scene(options.common, widths);
  const std::vector<Design> designs = designs_from(options.common.designs);
  create_output_folder(options.out);
  const OutputFolderLock lock(options.out);
  std::cout << provenance(scene.scene, widths) << std::flush;
  const int width = scene.scene.width, height = scene.scene.height;
  const size_t pixel_count = size_t(width) * size_t(height);

  // Visibility from the exact reference: the nearest triangle (largest 1/w) owns a pixel.
  std::vector<int64_t> owner(pixel_count, -1);
  std::vector<double> nearest(pixel_count, 0), exact_u(pixel_count, 0), exact_v(pixel_count, 0);
  const Design& probe = find_design("divide");
  ScanUnit coverage(probe, widths, width, height);
  std::vector<Fragment> fragments;
  for (size_t t = 0; t < scene.unit.size(); ++t) {
    throw_if_interrupted();
    fragments.clear();
    coverage.compute(scene.unit[t], &fragments);  // values only: no cycles
    if (fragments.empty()) continue;
    const ExactReference exact(scene.scene.triangles[t], scene.unit[t], widths.subpixel_bits);
    for (const Fragment& f : fragments) {
      const size_t at = size_t(f.y) * size_t(width) + size_t(f.x);
      const ExactSample s = exact.at_pixel(f.x, f.y);
      if (owner[at] >= 0 && double(s.q) <= nearest[at]) continue;
      owner[at] = int64_t(t);
      nearest[at] = double(s.q);
      exact_u[at] = double(s.u);
      exact_v[at] = double(s.v);
    }
  }
  Image exact_image(width, height);
  for (size_t at = 0; at < pixel_count; ++at)
    if (owner[at] >= 0)
      exact_image.set(int(at % size_t(width)), int(at / size_t(width)), checker(exact_u[at], exact_v[at], options.checker_texels));

  // Every PNG is encoded first and all are written at the end, so that an
  // interrupted render leaves the previous set whole.
  std::vector<std::pair<std::filesystem::path, std::string>> files;
  std::string lines;
  const double lsb = std::ldexp(1.0, -widths.out_frac);
  for (const Design& d : designs) {
    ScanUnit unit(d, widths, width, height);
    Image side(2 * width, height), heat_map(width, height);
    double sum = 0;
    int64_t count = 0;
    for (size_t t = 0; t < scene.unit.size(); ++t) {
      throw_if_interrupted();
      fragments.clear();
      unit.compute(scene.unit[t], &fragments);
      for (const Fragment& f : fragments) {
        const size_t at = size_t(f.y) * size_t(width) + size_t(f.x);
        if (owner[at] != int64_t(t)) continue;
        const double u = double(f.u) * lsb, v = double(f.v) * lsb;
        side.set(f.x, f.y, checker(u, v, options.checker_texels));
        const double error = std::max(std::fabs(u - exact_u[at]), std::fabs(v - exact_v[at]));
        heat_map.set(f.x, f.y, heat(error));
        sum += error;
        ++count;
      }
    }
    for (int y = 0; y < height; ++y)
      std::copy_n(exact_image.pixels.begin() + ptrdiff_t(y) * width * 3, size_t(width) * 3,
                  side.pixels.begin() + (ptrdiff_t(y) * 2 * width + width) * 3);
    side.text(20, 20, d.name, {255, 220, 80}, 3);
    side.text(width + 20, 20, "exact", {255, 220, 80}, 3);
    heat_map.text(20, 20, d.name + " error", {255, 220, 80}, 3);
    heat_legend(heat_map);
    const std::string checker_path = (std::filesystem::path(options.out) / (d.name + "_checker.png")).string();
    const std::string heat_path = (std::filesystem::path(options.out) / (d.name + "_error.png")).string();
    files.emplace_back(checker_path, side.png(checker_path));
    files.emplace_back(heat_path, heat_map.png(heat_path));
    lines += fmt::format("{:<17} {:>10.3e}  {} {}\n", d.name, count ? sum / double(count) : 0.0,
                         checker_path, heat_path);
  }
  throw_if_interrupted();
  write_files_atomic(files);
  fmt::print("\n{:<17} {:>10}  {}\n{}", "design", "mean_err", "files", lines);
  fmt::print("visible pixels only (nearest triangle by exact 1/w); checker squares of {} texels\n",
             options.checker_texels);
  return 0;
}

}  // namespace cdsim
