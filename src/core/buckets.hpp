// Items grouped by a small integer key with a counting sort: linear, and stable (within a
// bucket, the items keep the order they were emitted in). Used wherever the mesh's tets are
// regrouped per vertex: faces and edges by their smallest vertex (quality report, HTML report,
// refinement's edge list) and the balls of the vertices (the optimizer).
#pragma once

#include <cstddef>
#include <vector>

namespace anitet {

// emit_all(emit) calls emit(key, value) once per item, key < num_keys, and must make the same
// calls each time: it runs twice (counting, then filling). Afterwards the values of key k are
// values[start[k] .. start[k + 1]). fill is scratch memory (kept by callers that call often).
template <class Index, class Value, class EmitAll>
void bucket_by_key(size_t num_keys, EmitAll&& emit_all, std::vector<Index>& start, std::vector<Value>& values,
                   std::vector<Index>& fill) {
  start.assign(num_keys + 1, 0);
  emit_all([&](size_t key, const Value&) { ++start[key + 1]; });
  for (size_t k = 0; k < num_keys; ++k) start[k + 1] += start[k];
  values.resize(start[num_keys]);
  fill.assign(start.begin(), start.end() - 1);
  emit_all([&](size_t key, const Value& value) { values[fill[key]++] = value; });
}

}  // namespace anitet
