#include "core/status.hpp"

namespace anitet {

const char* error_name(Error e) {
  switch (e) {
    case Error::Ok: return "ok";
    case Error::InvalidArgument: return "invalid_argument";
    case Error::FileNotFound: return "file_not_found";
    case Error::Parse: return "parse_error";
    case Error::UnsupportedFormat: return "unsupported_format";
    case Error::EmptyInput: return "empty_input";
    case Error::BufferTooSmall: return "buffer_too_small";
    case Error::NonFiniteCoordinate: return "non_finite_coordinate";
    case Error::DegenerateTriangle: return "degenerate_triangle";
    case Error::DuplicateTriangle: return "duplicate_triangle";
    case Error::OpenBoundary: return "open_boundary";
    case Error::NonManifoldEdge: return "non_manifold_edge";
    case Error::NonManifoldVertex: return "non_manifold_vertex";
    case Error::InconsistentOrientation: return "inconsistent_orientation";
    case Error::SelfIntersection: return "self_intersection";
    case Error::IntersectingShells: return "intersecting_shells";
    case Error::BadIndex: return "bad_index";
    case Error::NotImplemented: return "not_implemented";
    case Error::Cancelled: return "cancelled";
    case Error::DuplicatePoint: return "duplicate_point";
    case Error::RecoveryFailed: return "recovery_failed";
    case Error::InvalidMesh: return "invalid_mesh";
    case Error::OutOfMemory: return "out_of_memory";
    case Error::Internal: return "internal_error";
  }
  return "unknown_error";
}

}  // namespace anitet
