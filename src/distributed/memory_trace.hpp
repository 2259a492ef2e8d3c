// A rank's resident memory after each phase of run_rank_parts, for profiling where its peak is
// (ANITET_RANK_MEMORY set: one line per phase on stderr; unset: nothing, no cost but a getenv).
#pragma once

namespace anitet::distributed {

// Prints "rank R: PHASE: RSS now, peak so far" (MiB) when ANITET_RANK_MEMORY is set.
void trace_memory(int rank, const char* phase);

}  // namespace anitet::distributed
