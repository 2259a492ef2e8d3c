// Text output formatted on every core (internal header): the items' lines are formatted in blocks
// by parallel tasks, a bounded window of blocks at a time, and appended (or handed to a writer) in
// order, so the text is the same as one loop's and at most one window (16 blocks) is held besides
// it. (Formatting the numbers is nearly all of a text writer's time.)
#pragma once

#include <algorithm>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include <tbb/parallel_for.h>

namespace anitet {

// Hands the text of format_item(text, i) for i = 0 .. count-1 to sink(std::string_view), in
// that order, a block at a time (a writer streams it to its file: no copy of the whole text).
template <class Sink, class FormatItem>
void write_items(Sink&& sink, size_t count, FormatItem&& format_item) {
  constexpr size_t kBlock = 16384, kWindow = 16;
  std::vector<std::string> texts(std::min(kWindow, (count + kBlock - 1) / kBlock));
  for (size_t w = 0; w < count; w += kBlock * kWindow) {
    const size_t blocks = std::min(kWindow, (count - w + kBlock - 1) / kBlock);
    tbb::parallel_for(size_t(0), blocks, [&](size_t b) {
      std::string& text = texts[b];
      text.clear();
      const size_t first = w + b * kBlock, last = std::min(count, first + kBlock);
      for (size_t i = first; i < last; ++i) format_item(text, i);
    });
    for (size_t b = 0; b < blocks; ++b) sink(std::string_view(texts[b]));
  }
}

// Appends format_item(text, i) for i = 0 .. count-1 to out, in that order.
template <class FormatItem>
void append_items(std::string& out, size_t count, FormatItem&& format_item) {
  write_items([&out](std::string_view text) { out += text; }, count, format_item);
}

}  // namespace anitet
