// Per-vertex fields: anitet_fields around anitet::VertexFields (.sol/.solb through io/sol_io.hpp)
// and their transfer from one mesh to another's vertices (metric/field_transfer.hpp).
#include <memory>
#include <string>
#include <vector>

#include "handles.hpp"
#include "io/sol_io.hpp"
#include "metric/field_transfer.hpp"
#include "shim.hpp"

using namespace anitet::capi;

static_assert(ANITET_FIELD_KIND_SCALAR == int(anitet::FieldKind::Scalar) &&
                  ANITET_FIELD_KIND_VECTOR == int(anitet::FieldKind::Vector) &&
                  ANITET_FIELD_KIND_SYM_TENSOR == int(anitet::FieldKind::SymTensor),
              "ANITET_FIELD_KIND_* differ from anitet::FieldKind");
static_assert(ANITET_TENSORS_AUTO == int(anitet::metric::TensorInterpolation::Auto) &&
                  ANITET_TENSORS_LOG_EUCLIDEAN == int(anitet::metric::TensorInterpolation::LogEuclidean) &&
                  ANITET_TENSORS_LINEAR == int(anitet::metric::TensorInterpolation::Linear),
              "ANITET_TENSORS_* differ from anitet::metric::TensorInterpolation");

namespace {

int bad(const char* fn, const std::string& what) {
  return set_error(ANITET_ERR_INVALID_ARGUMENT, std::string(fn) + ": " + what);
}

}  // namespace

extern "C" {

int anitet_fields_create(const int32_t* kinds, int32_t num_fields, const double* values, int64_t num_values,
                         anitet_fields** out) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (out == nullptr) return null_argument(fn, "out");
    *out = nullptr;
    if (num_fields < 1) return bad(fn, "num_fields is " + std::to_string(num_fields) + ", at least 1 needed");
    if (kinds == nullptr) return null_argument(fn, "kinds");
    if (num_values < 0) return bad(fn, "num_values is negative");
    if (num_values == 0) return set_error(ANITET_ERR_EMPTY_INPUT, std::string(fn) + ": no value");
    if (values == nullptr) return null_argument(fn, "values");
    auto fields = std::make_unique<anitet_fields>();
    anitet::VertexFields& f = fields->fields;
    for (int32_t i = 0; i < num_fields; ++i) {
      if (kinds[i] < ANITET_FIELD_KIND_SCALAR || kinds[i] > ANITET_FIELD_KIND_SYM_TENSOR)
        return bad(fn, "kind " + std::to_string(i) + " is " + std::to_string(kinds[i]) +
                           ", not an ANITET_FIELD_KIND_* value (1, 2 or 3)");
      f.kinds.push_back(static_cast<anitet::FieldKind>(kinds[i]));
    }
    const int64_t record = int64_t(f.record_size());
    if (num_values % record != 0)
      return bad(fn, "num_values " + std::to_string(num_values) + " is not a whole number of records of " +
                         std::to_string(record) + " values (the fields' components per vertex)");
    f.values.assign(values, values + num_values);
    *out = fields.release();
    return ok();
  });
}

int anitet_fields_read(const char* path, anitet_fields** out) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (out == nullptr) return null_argument(fn, "out");
    *out = nullptr;
    if (path == nullptr) return null_argument(fn, "path");
    anitet::Result<anitet::VertexFields> read = anitet::read_vertex_fields(std::string(path));
    if (!read.ok()) return set_status(fn, read.status());
    auto fields = std::make_unique<anitet_fields>();
    fields->fields = std::move(read).value();
    *out = fields.release();
    return ok();
  });
}

int anitet_fields_write(const anitet_fields* fields, const char* path) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (fields == nullptr) return null_argument(fn, "fields");
    if (path == nullptr) return null_argument(fn, "path");
    return set_status(fn, anitet::write_vertex_fields(fields->fields, std::string(path)));
  });
}

void anitet_fields_destroy(anitet_fields* fields) { delete fields; }

int anitet_fields_get_counts(const anitet_fields* fields, int32_t* num_fields, int32_t* record_size,
                             int64_t* num_vertices) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (fields == nullptr) return null_argument(fn, "fields");
    const anitet::VertexFields& f = fields->fields;
    if (num_fields) *num_fields = int32_t(f.kinds.size());
    if (record_size) *record_size = int32_t(f.record_size());
    if (num_vertices) *num_vertices = int64_t(f.num_vertices());
    return ok();
  });
}

int anitet_fields_get_kinds(const anitet_fields* fields, int32_t* kinds, int64_t kinds_len) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (fields == nullptr) return null_argument(fn, "fields");
    return fill(fn, "kinds", fields->fields.kinds, kinds, kinds_len,
                [](anitet::FieldKind k) { return static_cast<int32_t>(k); });
  });
}

int anitet_fields_get_values(const anitet_fields* fields, double* values, int64_t values_len) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (fields == nullptr) return null_argument(fn, "fields");
    return fill(fn, "values", fields->fields.values, values, values_len, kSame);
  });
}

int anitet_fields_get_data(const anitet_fields* fields, const double** data, int64_t* count) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (fields == nullptr) return null_argument(fn, "fields");
    if (data == nullptr) return null_argument(fn, "data");
    if (count == nullptr) return null_argument(fn, "count");
    *data = fields->fields.values.data();
    *count = int64_t(fields->fields.values.size());
    return ok();
  });
}

}  // extern "C"

namespace {

// The transfer in a task arena of num_threads threads (0: all cores).
int transfer(const char* fn, const anitet_mesh* from, const anitet_fields* fields, const anitet_mesh* to,
             int32_t tensors, int32_t num_threads, anitet_fields** out) {
  return guard(fn, [&] {
    if (out == nullptr) return null_argument(fn, "out");
    *out = nullptr;
    if (from == nullptr) return null_argument(fn, "from");
    if (fields == nullptr) return null_argument(fn, "fields");
    if (to == nullptr) return null_argument(fn, "to");
    if (tensors < ANITET_TENSORS_AUTO || tensors > ANITET_TENSORS_LINEAR)
      return bad(fn, "tensors is " + std::to_string(tensors) + ", not ANITET_TENSORS_AUTO, _LOG_EUCLIDEAN or _LINEAR");
    if (num_threads < 0) return bad(fn, "num_threads is " + std::to_string(num_threads) + ", not >= 0");
    anitet::metric::TransferReport report;
    anitet::Result<anitet::VertexFields> moved = in_arena(num_threads, [&] {
      return anitet::metric::transfer_fields(from->mesh, fields->fields, to->mesh.xyz,
                                             static_cast<anitet::metric::TensorInterpolation>(tensors), &report);
    });
    if (!moved.ok()) return set_status(fn, moved.status());
    auto result = std::make_unique<anitet_fields>();
    result->fields = std::move(moved).value();
    result->transfer = std::make_unique<anitet::metric::TransferReport>(std::move(report));
    *out = result.release();
    return ok();
  });
}

}  // namespace

extern "C" {

int anitet_mesh_transfer_fields(const anitet_mesh* from, const anitet_fields* fields, const anitet_mesh* to,
                                int32_t tensors, anitet_fields** out) {
  return transfer(__func__, from, fields, to, tensors, 0, out);
}

int anitet_mesh_transfer_fields_ext(const anitet_mesh* from, const anitet_fields* fields, const anitet_mesh* to,
                                    int32_t tensors, int32_t num_threads, anitet_fields** out) {
  return transfer(__func__, from, fields, to, tensors, num_threads, out);
}

int anitet_fields_get_transfer_report(const anitet_fields* fields, int64_t* outside, double* max_outside_distance,
                                      int32_t* log_euclidean, int64_t log_euclidean_len) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (fields == nullptr) return null_argument(fn, "fields");
    if (!fields->transfer) return bad(fn, "the fields were not made by anitet_mesh_transfer_fields");
    const anitet::metric::TransferReport& r = *fields->transfer;
    if (log_euclidean) {
      const int code = fill(fn, "log_euclidean", r.log_euclidean, log_euclidean, log_euclidean_len,
                            [](bool b) { return int32_t(b ? 1 : 0); });
      if (code != ANITET_OK) return code;
    }
    if (outside) *outside = int64_t(r.outside);
    if (max_outside_distance) *max_outside_distance = r.max_outside_distance;
    return ok();
  });
}

}  // extern "C"
