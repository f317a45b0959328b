#include "netlist_writer.hpp"

#include <fmt/format.h>

#include <cctype>
#include <iterator>
#include <stdexcept>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "cache_files.hpp"

namespace cdsim {
namespace {

bool is_keyword(const std::string& name) {
  static const std::unordered_set<std::string> keywords = {
      "always", "and", "assign", "begin", "buf", "case", "default", "else", "end", "endcase", "endmodule",
      "for", "function", "if", "initial", "inout", "input", "integer", "module", "nand", "negedge", "nor",
      "not", "or", "output", "parameter", "posedge", "reg", "supply0", "supply1", "task", "tri", "wire",
      "xnor", "xor"};
  return keywords.count(name) != 0;
}

// A Verilog identifier for `name`: as it is if it is a simple one, else
// escaped (a backslash before, a space after).
std::string identifier(const std::string& name) {
  bool simple = !name.empty() && (std::isalpha(static_cast<unsigned char>(name[0])) || name[0] == '_');
  for (const char c : name) simple = simple && (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '$');
  if (simple && !is_keyword(name)) return name;
  for (const char c : name)
    if (std::isspace(static_cast<unsigned char>(c)) || !std::isprint(static_cast<unsigned char>(c)))
      throw std::runtime_error(fmt::format("netlist: the name '{}' cannot be a Verilog identifier", name));
  return "\\" + name + " ";
}

// A bit of a connection: a net number, or a constant "0", "1", "x", "z".
std::string constant(const nlohmann::json& bit) {
  const std::string c = bit.get<std::string>();
  if (c == "0" || c == "1" || c == "x" || c == "z") return "1'b" + c;
  throw std::runtime_error(fmt::format("netlist: unknown bit '{}'", c));
}

void write_module(const std::string& name, const nlohmann::json& module, const nlohmann::json& modules,
                  fmt::memory_buffer& out) {
  // Each net's name: the first input port bit on it, else the first port
  // bit, else a wire of its own.
  std::unordered_map<int64_t, std::string> net_name;
  struct PortBit {
    std::string name;  // the port, or port[i] for a port of several bits
    const nlohmann::json* bit;
  };
  std::vector<PortBit> outputs;
  std::string header, declarations;
  const nlohmann::json& ports = module.at("ports");
  for (const bool inputs_first : {true, false})
    for (const auto& [port, info] : ports.items()) {
      const bool input = info.at("direction").get<std::string>() == "input";
      if (input != inputs_first) continue;
      const nlohmann::json& bits = info.at("bits");
      const std::string id = identifier(port);
      header += (header.empty() ? "" : ", ") + id;
      const std::string direction = info.at("direction").get<std::string>();
      declarations += bits.size() == 1 ? fmt::format("  {} {};\n", direction, id)
                                       : fmt::format("  {} [{}:0] {};\n", direction, bits.size() - 1, id);
      for (size_t i = 0; i < bits.size(); ++i) {
        const std::string bit_name = bits.size() == 1 ? id : fmt::format("{}[{}]", id, i);
        if (bits[i].is_number_integer() && net_name.emplace(bits[i].get<int64_t>(), bit_name).second) continue;
        if (direction == "output") outputs.push_back({bit_name, &bits[i]});
      }
    }
  const auto net = [&](const nlohmann::json& bit, std::string* wires) -> std::string {
    if (!bit.is_number_integer()) return constant(bit);
    const int64_t n = bit.get<int64_t>();
    const auto [it, added] = net_name.emplace(n, fmt::format("_n{}_", n));
    if (added && wires) fmt::format_to(std::back_inserter(*wires), "  wire {};\n", it->second);
    return it->second;
  };
  std::string wires;
  fmt::memory_buffer cells;
  int64_t hidden = 0;
  for (const auto& [cell_name, cell] : module.at("cells").items()) {
    const std::string type = cell.at("type").get<std::string>();
    if (!type.empty() && type[0] == '$' && !modules.contains(type))
      throw std::runtime_error(fmt::format("netlist: cell {} of {} is Yosys's internal {}", cell_name, name, type));
    const bool hide = cell.value("hide_name", 0) != 0;
    fmt::format_to(std::back_inserter(cells), "  {} {} (", identifier(type),
                   hide ? fmt::format("_c{}_", hidden++) : identifier(cell_name));
    bool first = true;
    for (const auto& [pin, bits] : cell.at("connections").items()) {
      std::string value;
      if (bits.size() == 1) {
        value = net(bits[0], &wires);
      } else if (!bits.empty()) {
        value = "{";
        for (size_t i = bits.size(); i-- > 0;) value += net(bits[i], &wires) + (i ? ", " : "");
        value += "}";
      }
      fmt::format_to(std::back_inserter(cells), "{}\n    .{}({})", first ? "" : ",", identifier(pin), value);
      first = false;
    }
    fmt::format_to(std::back_inserter(cells), "\n  );\n");
  }
  // Output port bits that another port names, or that are constant.
  std::string assigns;
  for (const PortBit& p : outputs) assigns += fmt::format("  assign {} = {};\n", p.name, net(*p.bit, &wires));
  fmt::format_to(std::back_inserter(out), "module {}({});\n{}{}{}", identifier(name), header, declarations, wires,
                 assigns);
  out.append(cells.data(), cells.data() + cells.size());
  fmt::format_to(std::back_inserter(out), "endmodule\n\n");
}

}  // namespace

std::vector<std::pair<std::string, std::string>> verilog_modules_from_yosys_json(const nlohmann::json& netlist) {
  std::vector<std::pair<std::string, std::string>> modules;
  for (const auto& [name, module] : netlist.at("modules").items()) {
    const nlohmann::json& attributes = module.value("attributes", nlohmann::json::object());
    if (attributes.contains("blackbox")) continue;
    fmt::memory_buffer out;
    write_module(name, module, netlist.at("modules"), out);
    modules.emplace_back(name, fmt::to_string(out));
  }
  return modules;
}

std::string verilog_from_modules(const std::vector<std::pair<std::string, std::string>>& modules) {
  std::string out = "// cdsim: structural Verilog from Yosys's write_json (app/netlist_writer.cpp)\n\n";
  for (const auto& [name, text] : modules) out += text;
  return out;
}

std::string verilog_from_yosys_json(const nlohmann::json& netlist) {
  return verilog_from_modules(verilog_modules_from_yosys_json(netlist));
}

void write_verilog_from_yosys_json(const std::filesystem::path& json_path,
                                   const std::filesystem::path& verilog_path) {
  const nlohmann::json netlist = nlohmann::json::parse(read_text_file(json_path));
  write_file_atomic(verilog_path, verilog_from_yosys_json(netlist));
}

}  // namespace cdsim
