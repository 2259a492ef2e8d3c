#include "io/patch_names.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <set>

namespace anitet {

namespace {

std::string trim(const std::string& s) {
  size_t b = 0, e = s.size();
  while (b < e && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
  while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
  return s.substr(b, e - b);
}

std::string labelled(const char* prefix, int32_t label) {
  return std::string(prefix) + (label < 0 ? "_m" + std::to_string(-int64_t{label}) : std::to_string(label));
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

constexpr size_t kMaxNameLength = 32;  // CGNS node names and Exodus names (MAX_STR_LENGTH)

bool name_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

// `text` as a valid name, maybe not unique; "" when nothing of it is usable.
std::string valid_name(const std::string& text) {
  std::string out;
  bool gap = false;  // a run of invalid characters since the last valid one
  for (char c : text) {
    if (!name_char(c)) {
      gap = true;
      continue;
    }
    if (gap && !out.empty()) out += '_';
    gap = false;
    out += c;
  }
  if (out.empty()) return out;
  if (!std::isalpha(static_cast<unsigned char>(out[0]))) out = "patch_" + out;
  out.resize(std::min(out.size(), kMaxNameLength));
  return out;
}

}  // namespace

Status check_patch_name(const std::string& name) {
  if (name.empty()) return Status(Error::InvalidArgument, "empty patch name");
  if (name.size() > kMaxNameLength) {
    return Status(Error::InvalidArgument, "patch name '" + name + "' is longer than 32 characters");
  }
  if (!std::isalpha(static_cast<unsigned char>(name[0]))) {
    return Status(Error::InvalidArgument, "patch name '" + name + "' must start with a letter");
  }
  for (char c : name) {
    if (!name_char(c)) {
      return Status(Error::InvalidArgument, "patch name '" + name +
                                                "' may only contain letters, digits and '_' (valid in "
                                                "SU2, OpenFOAM, CGNS and Exodus)");
    }
  }
  return Status::success();
}

namespace {

// Splits "LABEL=VALUE,LABEL=VALUE,..." (one trailing comma allowed) and calls
// on_item(item, label_text, label, value) for each item, values trimmed; stops at the first
// error, its or on_item's. `value_kind` names VALUE in the messages ("NAME", "TYPE").
template <class OnItem>
Status for_each_label_item(const std::string& spec, const char* value_kind, OnItem&& on_item) {
  size_t start = 0, items = 0;
  while (start <= spec.size()) {
    size_t comma = spec.find(',', start);
    if (comma == std::string::npos) comma = spec.size();
    const std::string item = trim(spec.substr(start, comma - start));
    start = comma + 1;
    if (item.empty()) {
      if (comma == spec.size() && items > 0) break;  // a trailing comma
      return Status(Error::InvalidArgument,
                    "'" + spec + "': empty item (expected LABEL=" + value_kind + ",...)");
    }
    const size_t eq = item.find('=');
    if (eq == std::string::npos) {
      return Status(Error::InvalidArgument, "'" + item + "' is not LABEL=" + value_kind);
    }
    const std::string label_text = trim(item.substr(0, eq)), value = trim(item.substr(eq + 1));
    int32_t label = 0;
    const char* first = label_text.data();
    const char* last = first + label_text.size();
    auto [ptr, ec] = std::from_chars(first, last, label);
    if (label_text.empty() || ec != std::errc() || ptr != last) {
      return Status(Error::InvalidArgument, "'" + item + "': '" + label_text +
                                                "' is not an integer patch label");
    }
    if (Status s = on_item(item, label_text, label, value); !s.ok()) return s;
    ++items;
  }
  return Status::success();
}

}  // namespace

Result<PatchNames> parse_patch_names(const std::string& spec) {
  PatchNames names;
  std::set<std::string> seen;
  Status parsed = for_each_label_item(spec, "NAME", [&](const std::string& item, const std::string& label_text,
                                                        int32_t label, const std::string& name) -> Status {
    if (Status s = check_patch_name(name); !s.ok()) {
      return Status(Error::InvalidArgument, "'" + item + "': " + s.message());
    }
    if (names.count(label)) {
      return Status(Error::InvalidArgument, "label " + label_text + " is named twice");
    }
    if (!seen.insert(name).second) {
      return Status(Error::InvalidArgument, "the name '" + name + "' is given twice");
    }
    names[label] = name;
    return Status::success();
  });
  if (!parsed.ok()) return parsed;
  return names;
}

PatchNames patch_names_from_text(const std::map<int32_t, std::string>& texts) {
  std::map<int32_t, std::string> wanted;
  std::set<std::string> taken;
  for (const auto& [label, text] : texts) {
    std::string name = valid_name(text);
    if (name.empty()) {
      taken.insert(labelled("patch", label));  // the default name it keeps
    } else {
      wanted[label] = std::move(name);
    }
  }
  PatchNames names;
  for (const auto& [label, base] : wanted) {
    std::string name = base;
    for (int n = 2; taken.count(name); ++n) {
      const std::string suffix = "_" + std::to_string(n);
      name = base.substr(0, kMaxNameLength - suffix.size()) + suffix;
    }
    taken.insert(name);
    names[label] = name;
  }
  return names;
}

std::string patch_name(const PatchNames& names, int32_t label) {
  auto it = names.find(label);
  return it != names.end() ? it->second : labelled("patch", label);
}

std::string region_name(int32_t label) { return labelled("region", label); }

Result<std::vector<NamedPatch>> named_patches(const std::vector<int32_t>& labels, const PatchNames& names,
                                              const PatchTypes& types) {
  std::set<int32_t> used(labels.begin(), labels.end());
  for (const auto& [label, name] : names) {
    if (Status s = check_patch_name(name); !s.ok()) return s;
    if (!used.count(label)) {
      return Status(Error::InvalidArgument, "patch label " + std::to_string(label) + " (named '" + name +
                                                "') is on no boundary triangle of the mesh");
    }
  }
  for (const auto& [label, kind] : types) {
    if (!used.count(label)) {
      return Status(Error::InvalidArgument, "patch label " + std::to_string(label) + " (of type " +
                                                patch_kind_name(kind) + ") is on no boundary triangle of the mesh");
    }
  }
  std::vector<NamedPatch> out;
  std::map<std::string, int32_t> by_name;
  for (int32_t label : used) {
    NamedPatch p{label, patch_name(names, label)};
    p.kind = patch_kind(types, label, p.name);
    auto [it, fresh] = by_name.emplace(p.name, label);
    if (!fresh) {
      return Status(Error::InvalidArgument, "patch labels " + std::to_string(it->second) + " and " +
                                                std::to_string(label) + " would both be named '" + p.name + "'");
    }
    out.push_back(std::move(p));
  }
  return out;
}

PatchKind patch_kind(const std::string& name) {
  const std::string l = lower(name);
  auto has = [&](const char* word) { return l.find(word) != std::string::npos; };
  if (has("inlet") || has("inflow")) return PatchKind::Inlet;
  if (has("outlet") || has("outflow")) return PatchKind::Outlet;
  if (has("farfield")) return PatchKind::Farfield;
  if (has("symmetry")) return PatchKind::Symmetry;
  return PatchKind::Wall;
}

PatchKind patch_kind(const PatchTypes& types, int32_t label, const std::string& name) {
  auto it = types.find(label);
  return it != types.end() ? it->second : patch_kind(name);
}

const char* patch_kind_name(PatchKind kind) {
  switch (kind) {
    case PatchKind::Inlet: return "inlet";
    case PatchKind::Outlet: return "outlet";
    case PatchKind::Farfield: return "farfield";
    case PatchKind::Symmetry: return "symmetry";
    case PatchKind::Patch: return "patch";
    case PatchKind::Wall: break;
  }
  return "wall";
}

Result<PatchTypes> parse_patch_types(const std::string& spec) {
  PatchTypes types;
  Status parsed = for_each_label_item(spec, "TYPE", [&](const std::string& item, const std::string& label_text,
                                                        int32_t label, const std::string& value) -> Status {
    const std::string type = lower(value);
    bool known = false;
    for (PatchKind kind : {PatchKind::Wall, PatchKind::Inlet, PatchKind::Outlet, PatchKind::Farfield,
                           PatchKind::Symmetry, PatchKind::Patch})
      if (type == patch_kind_name(kind)) {
        if (!types.emplace(label, kind).second)
          return Status(Error::InvalidArgument, "label " + label_text + " is given a type twice");
        known = true;
      }
    if (!known)
      return Status(Error::InvalidArgument, "'" + item + "': unknown type '" + type +
                                                "' (wall, inlet, outlet, farfield, symmetry or patch)");
    return Status::success();
  });
  if (!parsed.ok()) return parsed;
  return types;
}

std::map<int32_t, int32_t> positive_ids(const std::vector<int32_t>& sorted_unique_labels) {
  std::map<int32_t, int32_t> ids;
  const bool all_positive = !sorted_unique_labels.empty() && sorted_unique_labels.front() > 0;
  int32_t next = 1;
  for (int32_t label : sorted_unique_labels) ids[label] = all_positive ? label : next++;
  return ids;
}

}  // namespace anitet
