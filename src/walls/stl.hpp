#pragma once
// STL files (ASCII and binary) to and from a host TriangleMesh.
//
// Format detection: a binary STL is an 80-byte header, a little-endian uint32
// triangle count n and n records of 50 bytes, so its size is exactly
// 84 + 50 n. A file of that size is read as binary even when its header starts
// with "solid" (many exporters write that); otherwise a file that starts with
// "solid" and holds only text is read as ASCII; anything else is reported as a
// truncated or corrupt binary file. Facet normals are ignored: orientation
// comes from the vertex order (counter-clockwise seen from outside), as the
// format specifies.
#include <string>

#include "walls/triangle_mesh.hpp"

namespace gs {

struct StlReadOptions {
  double scale = 1;           // coordinates are multiplied by this (1e-3 for a file in mm)
  double weld_tolerance = 0;  // [m, after scaling] merge corners closer than this; 0: only equal ones
};

// Reads an STL file, shares equal (or, with a tolerance, close) corners as one
// vertex, and validates the result. Throws std::runtime_error naming the file
// (and for ASCII the line) on: a missing or unreadable file, a truncated or
// oversized binary file, malformed ASCII, a NaN or infinite coordinate, a
// degenerate (zero-area) triangle, an empty file.
TriangleMesh read_stl(const std::string& path, const StlReadOptions& options = {});

enum class StlFormat { binary, ascii };

// Writes the mesh; binary stores coordinates as float32 (about 7 significant
// digits), ASCII with 17 significant digits (exact round trip of doubles).
// Facet normals are written from the winding. Throws std::runtime_error when
// the file cannot be written.
void write_stl(const std::string& path, const TriangleMesh& mesh, StlFormat format = StlFormat::binary);

}  // namespace gs
