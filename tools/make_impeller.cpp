// Writes the seed paper's reference impeller (Radeke et al. 2010, Table 1) as
// a binary STL in metres: hub and shaft (one closed shell) and four flat
// pitched blades (closed boxes buried in the hub). cases/mixer/README.md lists
// the dimensions. Usage:
//   make_impeller OUTPUT.stl [--segments N] [--blade-thickness M] [--shaft-length M]
//                            [--blade-angle DEG] [--ascii]
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <stdexcept>
#include <string>

#include "walls/impeller.hpp"
#include "walls/stl.hpp"

namespace {

void usage(const char* program) {
  std::fprintf(stderr,
               "usage: %s OUTPUT.stl [--segments N] [--blade-thickness M] [--shaft-length M]\n"
               "       [--blade-angle DEG] [--ascii]\n"
               "Writes the four-bladed reference impeller (lengths in metres, axis +z,\n"
               "hub bottom centre at the origin).\n",
               program);
}

double number(const char* text, const std::string& option) {
  char* end = nullptr;
  const double v = std::strtod(text, &end);
  if (end == text || *end != '\0') throw std::runtime_error(option + ": expected a number, got '" + text + "'");
  return v;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    gs::ImpellerSpec spec;
    std::string output;
    gs::StlFormat format = gs::StlFormat::binary;
    for (int i = 1; i < argc; ++i) {
      const std::string arg = argv[i];
      auto value = [&]() -> const char* {
        if (i + 1 >= argc) throw std::runtime_error(arg + ": missing value");
        return argv[++i];
      };
      if (arg == "--help" || arg == "-h") {
        usage(argv[0]);
        return 0;
      } else if (arg == "--segments") {
        spec.segments = int(number(value(), arg));
      } else if (arg == "--blade-thickness") {
        spec.blade_thickness = number(value(), arg);
      } else if (arg == "--shaft-length") {
        spec.shaft_length = number(value(), arg);
      } else if (arg == "--blade-angle") {
        spec.blade_angle_deg = number(value(), arg);
      } else if (arg == "--ascii") {
        format = gs::StlFormat::ascii;
      } else if (!arg.empty() && arg[0] == '-') {
        throw std::runtime_error("unknown option '" + arg + "'");
      } else if (output.empty()) {
        output = arg;
      } else {
        throw std::runtime_error("more than one output file given");
      }
    }
    if (output.empty()) {
      usage(argv[0]);
      return 2;
    }
    const gs::TriangleMesh mesh = gs::make_impeller(spec);
    gs::write_stl(output, mesh, format);
    const gs::MeshTopology topo = gs::mesh_topology(mesh);
    std::printf("%s: %zu triangles, %zu vertices, volume %.6e m^3, %s, %s\n", output.c_str(), mesh.triangles.size(),
                mesh.vertices.size(), gs::mesh_volume(mesh), topo.closed() ? "closed" : "NOT closed",
                topo.consistently_oriented() ? "consistently oriented" : "NOT consistently oriented");
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "make_impeller: %s\n", e.what());
    return 1;
  }
}
