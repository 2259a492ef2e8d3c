#include "cli_util.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <vector>

namespace anitet::cli {

namespace {

// Words of `text` wrapped to `width` columns; lines after the first indented by `indent`.
// Explicit line breaks in the text are kept.
std::string wrap(const std::string& text, size_t width, size_t indent) {
  std::string out, line;
  auto flush = [&](bool last) {
    out += line;
    if (!last) out += "\n" + std::string(indent, ' ');
    line.clear();
  };
  std::istringstream paragraphs(text);
  std::string paragraph;
  bool first_paragraph = true;
  while (std::getline(paragraphs, paragraph)) {
    if (!first_paragraph) flush(false);
    first_paragraph = false;
    std::istringstream words(paragraph);
    std::string word;
    while (words >> word) {
      if (!line.empty() && indent + line.size() + 1 + word.size() > width) flush(false);
      line += (line.empty() ? "" : " ") + word;
    }
  }
  flush(true);
  return out;
}

class WrappingFormatter final : public CLI::Formatter {
 public:
  WrappingFormatter() { column_width(28); }
  std::string make_option(const CLI::Option* opt, bool is_positional) const override {
    const std::string name = "  " + make_option_name(opt, is_positional) + make_option_opts(opt);
    const std::string desc = make_option_desc(opt);
    std::string out = name;
    if (desc.empty()) return out + "\n";
    if (name.size() + 1 > get_column_width()) out += "\n" + std::string(get_column_width(), ' ');
    else out += std::string(get_column_width() - name.size(), ' ');
    return out + wrap(desc, kHelpWidth, get_column_width()) + "\n";
  }
  std::string make_subcommand(const CLI::App* sub) const override {
    std::string name = "  " + sub->get_display_name(true);
    name += std::string(name.size() < get_column_width() ? get_column_width() - name.size() : 1, ' ');
    return name + wrap(sub->get_description(), kHelpWidth, get_column_width()) + "\n";
  }
  std::string make_description(const CLI::App* app) const override {
    const std::string d = app->get_description();
    return d.empty() ? d : wrap(d, kHelpWidth, 0) + "\n";
  }
};

// The number in `text`, or why not.
bool parse_number(const std::string& text, double& value) {
  std::istringstream in(text);
  in >> value;
  return !in.fail() && in.eof() && std::isfinite(value);
}

std::string shown(double x) {
  std::ostringstream os;
  os << x;  // 1, 0.5, 1e+30: no 309-digit expansion of the largest double
  return os.str();
}

size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

}  // namespace

std::shared_ptr<CLI::Formatter> wrapping_formatter() { return std::make_shared<WrappingFormatter>(); }

CLI::Validator positive() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        double x = 0;
        if (!parse_number(text, x)) return "must be a number, got '" + text + "'";
        return x > 0 ? std::string() : "must be > 0, got " + text;
      },
      "> 0");
}

CLI::Validator non_negative() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        double x = 0;
        if (!parse_number(text, x)) return "must be a number, got '" + text + "'";
        return x >= 0 ? std::string() : "must be >= 0, got " + text;
      },
      ">= 0");
}

CLI::Validator in_range(double lo, double hi) {
  return CLI::Validator(
      [lo, hi](std::string& text) -> std::string {
        double x = 0;
        if (!parse_number(text, x)) return "must be a number, got '" + text + "'";
        return x >= lo && x <= hi ? std::string() : "must be in " + shown(lo) + " .. " + shown(hi) + ", got " + text;
      },
      shown(lo) + " .. " + shown(hi));
}

std::string suggest_option(const CLI::App& cmd, const std::string& unknown) {
  if (unknown.size() < 3 || unknown.compare(0, 2, "--") != 0) return "";
  const std::string asked = unknown.substr(2, unknown.find('=') == std::string::npos ? std::string::npos : unknown.find('=') - 2);
  std::string best;
  size_t best_distance = 3;
  for (const CLI::Option* opt : cmd.get_options()) {
    for (const std::string& name : opt->get_lnames()) {
      const size_t d = name.compare(0, asked.size(), asked) == 0 ? 1 : edit_distance(asked, name);
      if (d < best_distance) {
        best_distance = d;
        best = name;
      }
    }
  }
  return best.empty() ? "" : " (did you mean --" + best + "?)";
}

std::string format_seconds(double s) {
  char buf[64];
  if (!(s >= 0) || !std::isfinite(s)) return "-";
  if (s < 10) std::snprintf(buf, sizeof buf, "%.2f s", s);
  else if (s < 60) std::snprintf(buf, sizeof buf, "%.1f s", s);
  else if (s < 3600) std::snprintf(buf, sizeof buf, "%d min %02d s", int(s / 60), int(s) % 60);
  else std::snprintf(buf, sizeof buf, "%d h %02d min", int(s / 3600), int(s / 60) % 60);
  return buf;
}

ProgressLine::ProgressLine(bool enabled)
    : enabled_(enabled && isatty(STDERR_FILENO)), start_(std::chrono::steady_clock::now()) {}

bool ProgressLine::update(const std::string& stage, double fraction) {
  if (!enabled_) return true;
  fraction = std::clamp(fraction, 0.0, 1.0);
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const int width = 24, filled = int(fraction * width + 0.5);
  std::string text = "[" + std::string(size_t(filled), '#') + std::string(size_t(width - filled), ' ') + "] ";
  char pct[16];
  std::snprintf(pct, sizeof pct, "%3d%% ", int(fraction * 100 + 0.5));
  text += pct + stage + "  " + format_seconds(elapsed);
  // The time left, once the fraction says something (the first stages are short).
  if (fraction > 0.05 && fraction < 1.0 && elapsed > 0.5)
    text += ", about " + format_seconds(elapsed / fraction * (1.0 - fraction)) + " left";
  const size_t pad = last_width_ > text.size() ? last_width_ - text.size() : 0;
  last_width_ = text.size();
  std::fprintf(stderr, "\r%s%s", text.c_str(), std::string(pad, ' ').c_str());
  if (fraction >= 1.0) {
    std::fprintf(stderr, "\r%s\r", std::string(last_width_, ' ').c_str());
    last_width_ = 0;
  }
  std::fflush(stderr);
  return true;
}

}  // namespace anitet::cli
