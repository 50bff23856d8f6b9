#include "core/params.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

namespace gf {

// ---------------------------------------------------------------- Range

bool Range::contains(double v) const {
  if (std::isnan(v)) return false;
  const bool lowOk = minInclusive ? v >= min : v > min;
  const bool highOk = maxInclusive ? v <= max : v < max;
  return lowOk && highOk;
}

bool Range::unrestricted() const { return std::isinf(min) && std::isinf(max); }

std::string Range::describe() const {
  const bool hasMin = !std::isinf(min), hasMax = !std::isinf(max);
  if (!hasMin && !hasMax) return "any";
  if (hasMin && hasMax)
    return fmt::format("in {}{:g}, {:g}{}", minInclusive ? "[" : "(", min, max, maxInclusive ? "]" : ")");
  if (hasMin) return fmt::format("{} {:g}", minInclusive ? ">=" : ">", min);
  return fmt::format("{} {:g}", maxInclusive ? "<=" : "<", max);
}

// ---------------------------------------------------------------- suggestions

std::size_t editDistance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t substitution = prev[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1);
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, substitution});
    }
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

std::string closestMatch(std::string_view word, const std::vector<std::string>& candidates) {
  std::string best;
  std::size_t bestDistance = std::max<std::size_t>(2, word.size() / 3) + 1;
  for (const auto& c : candidates) {
    const std::size_t d = editDistance(word, c);
    if (d < bestDistance) {
      bestDistance = d;
      best = c;
    }
  }
  return best;
}

namespace {

std::string joinNames(const std::vector<std::string>& names) {
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i) out += (i ? ", " : "") + names[i];
  return out;
}

FileLocation locationOf(const std::string& file, const YAML::Node& node) {
  if (!node.IsDefined()) return {file, 0, 0};
  const YAML::Mark m = node.Mark();
  if (m.line < 0) return {file, 0, 0};
  return {file, m.line + 1, m.column + 1};
}

/// How a YAML node looks to a user, for "found ..." texts.
std::string describeNode(const YAML::Node& node) {
  if (!node.IsDefined() || node.IsNull()) return "nothing";
  if (node.IsSequence()) return fmt::format("a list of {} item(s)", node.size());
  if (node.IsMap()) return "a map";
  return fmt::format("'{}'", node.Scalar());
}

std::string formatReal(double v) { return fmt::format("{:g}", v); }
std::string formatVec(const Vec3& v) { return fmt::format("[{:g}, {:g}, {:g}]", v.x, v.y, v.z); }

}  // namespace

// ---------------------------------------------------------------- shared state

struct Params::Section {
  YAML::Node node;     // the map (undefined for an absent section)
  std::string prefix;  // dotted path of this section ("" for the root)
  std::set<std::string>* queried = nullptr;  // shared by every reader of the same map
};

struct Params::Shared {
  std::string file;
  bool documenting = false;
  std::vector<std::shared_ptr<Section>> sections;  // every map visited, in order
  std::map<std::string, std::set<std::string>> queriedByPrefix;  // keys asked for, per section path
  std::vector<ResolvedKey> resolved;
  std::vector<KeyDoc> docs;
  std::set<std::string> documentedPaths;
  /// A model of a choice whose reader is declaring keys (documentation mode), e.g. the model
  /// "lattice" of the choice "insertion[].type".
  struct ModelInChoice {
    std::string choicePath;
    std::string model;
  };
  std::vector<ModelInChoice> modelStack;  // outermost choice first
  struct Choice {
    std::string key;                  // "type"
    std::vector<std::string> models;  // every model of it, in the registry's order
  };
  std::map<std::string, Choice> choices;  // by choice path
  /// For each documented path, the help texts of its declarations, each distinct one once (models
  /// that share a key may explain it each for itself), and the model stack of each declaration.
  struct Declarations {
    std::vector<std::string> helps;
    std::vector<std::vector<ModelInChoice>> stacks;
    std::vector<std::string> defaults;  // of each declaration ("" = required)
  };
  std::map<std::string, Declarations> declarations;
};

Params::Params(std::shared_ptr<Shared> shared, std::shared_ptr<Section> section)
    : shared_(std::move(shared)), section_(std::move(section)) {
  section_->queried = &shared_->queriedByPrefix[section_->prefix];
  shared_->sections.push_back(section_);
}
Params::~Params() = default;
Params::Params(const Params&) = default;
Params& Params::operator=(const Params&) = default;
Params::Params(Params&&) noexcept = default;
Params& Params::operator=(Params&&) noexcept = default;

Params Params::loadString(const std::string& yamlText, const std::string& displayName) {
  auto shared = std::make_shared<Shared>();
  shared->file = displayName;
  YAML::Node root;
  try {
    root = YAML::Load(yamlText);
  } catch (const YAML::ParserException& e) {
    throw CaseError({displayName, e.mark.line + 1, e.mark.column + 1}, "(file)",
                    fmt::format("text that is not valid YAML ({})", e.msg), "a YAML map of case sections");
  }
  if (!root.IsDefined() || root.IsNull())
    throw CaseError({displayName, 0, 0}, "(file)", "an empty file", "a YAML map of case sections");
  if (!root.IsMap())
    throw CaseError(locationOf(displayName, root), "(file)", describeNode(root), "a YAML map of case sections");
  auto section = std::make_shared<Section>();
  section->node = root;
  return Params(shared, section);
}

Params Params::loadFile(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(path, ec))
    throw CaseError({path, 0, 0}, "(file)", "no such file", "a readable YAML case file");
  if (fs::is_directory(path, ec))
    throw CaseError({path, 0, 0}, "(file)", "a directory", "a readable YAML case file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw CaseError({path, 0, 0}, "(file)", "a file that cannot be opened", "a readable YAML case file");
  std::stringstream buffer;
  buffer << in.rdbuf();
  return loadString(buffer.str(), path);
}

Params Params::documentation() {
  auto shared = std::make_shared<Shared>();
  shared->file = "(documentation)";
  shared->documenting = true;
  return Params(shared, std::make_shared<Section>());
}

// ---------------------------------------------------------------- helpers

bool Params::documenting() const { return shared_->documenting; }
void Params::beginModelDocumentation(std::string_view choiceKey, const std::vector<std::string>& models,
                                     const std::string& model) {
  const std::string choicePath = path(choiceKey);
  shared_->choices[choicePath] = {std::string(choiceKey), models};
  shared_->modelStack.push_back({choicePath, model});
}
void Params::endModelDocumentation() {
  if (!shared_->modelStack.empty()) shared_->modelStack.pop_back();
}
const std::string& Params::fileName() const { return shared_->file; }

std::string Params::path(std::string_view key) const {
  if (section_->prefix.empty()) return std::string(key);
  if (key.empty()) return section_->prefix;
  return section_->prefix + "." + std::string(key);
}

const YAML::Node* Params::find(std::string_view key) const {
  static thread_local YAML::Node found;
  const YAML::Node& map = section_->node;
  if (!map.IsDefined() || !map.IsMap()) return nullptr;
  for (auto it = map.begin(); it != map.end(); ++it) {
    if (it->first.Scalar() == key) {
      found.reset(it->second);
      return &found;
    }
  }
  return nullptr;
}

bool Params::has(std::string_view key) const {
  const YAML::Node* n = find(key);
  return n != nullptr && !n->IsNull();
}

bool Params::isSequence(std::string_view key) const {
  const YAML::Node* n = find(key);
  return n != nullptr && n->IsSequence();
}

bool Params::isWord(std::string_view key, std::string_view word) const {
  const YAML::Node* n = find(key);
  return n != nullptr && n->IsScalar() && n->Scalar() == word;
}

FileLocation Params::location(std::string_view key) const {
  if (const YAML::Node* n = find(key)) {
    FileLocation loc = locationOf(shared_->file, *n);
    if (loc.line > 0) return loc;
  }
  return locationOf(shared_->file, section_->node);
}

void Params::fail(std::string_view key, const std::string& found, const std::string& expected) const {
  throw CaseError(location(key), path(key), found, expected);
}

void Params::markQueried(std::string_view key) const { section_->queried->insert(std::string(key)); }

void Params::document(const Key& k, std::string type, std::string defaultValue, std::string allowed) const {
  // In documentation mode, list items are all documented under "name[]".
  const std::string p = path(k.name);
  Shared::Declarations& declared = shared_->declarations[p];
  declared.stacks.push_back(shared_->modelStack);
  declared.defaults.push_back(defaultValue);
  if (std::find(declared.helps.begin(), declared.helps.end(), k.help) == declared.helps.end())
    declared.helps.emplace_back(k.help);
  if (!shared_->documentedPaths.insert(p).second) return;
  shared_->docs.push_back(
      {p, std::move(type), std::move(defaultValue), std::string(k.unit), std::move(allowed), std::string(k.help)});
}

void Params::record(const Key& k, std::string value, bool fromDefault) const {
  shared_->resolved.push_back({path(k.name), std::move(value), std::string(k.unit), fromDefault});
}

// ---------------------------------------------------------------- scalars

const YAML::Node* Params::lookup(const Key& k, const char* type, const std::string* defaultText,
                                 const std::string& allowed, const std::string& expected) const {
  markQueried(k.name);
  if (documenting()) {
    document(k, type, defaultText != nullptr ? *defaultText : "", allowed);
    return nullptr;
  }
  const YAML::Node* n = find(k.name);
  if (n != nullptr && !n->IsNull()) return n;
  if (defaultText == nullptr) fail(k.name, "nothing", expected + " (this key is required)");
  record(k, *defaultText, true);
  return nullptr;
}

namespace {

std::string numberExpected(const Key& k) { return fmt::format("a number [{}]", k.unit); }
std::string vectorExpected(const Key& k) { return fmt::format("a list of 3 numbers [x, y, z] [{}]", k.unit); }
std::string listExpected(const Key& k) { return fmt::format("a list of numbers [{}]", k.unit); }

/// Reads one node as a double, with a precise error on failure.
double parseReal(const Params& p, const Key& k, const YAML::Node& n) {
  if (!n.IsScalar()) p.fail(k.name, describeNode(n), numberExpected(k));
  double v = 0.0;
  try {
    v = n.as<double>();
  } catch (const YAML::Exception&) {
    p.fail(k.name, describeNode(n), numberExpected(k));
  }
  if (!std::isfinite(v)) p.fail(k.name, describeNode(n), fmt::format("a finite number [{}]", k.unit));
  if (!k.range.contains(v))
    p.fail(k.name, formatReal(v), fmt::format("a value {} [{}]", k.range.describe(), k.unit));
  return v;
}

long long parseInteger(const Params& p, const Key& k, const YAML::Node& n) {
  long long v = 0;
  if (!n.IsScalar()) p.fail(k.name, describeNode(n), "an integer");
  try {
    v = n.as<long long>();
  } catch (const YAML::Exception&) {
    p.fail(k.name, describeNode(n), "an integer");
  }
  if (!k.range.contains(static_cast<double>(v)))
    p.fail(k.name, std::to_string(v), fmt::format("an integer {}", k.range.describe()));
  return v;
}

Vec3 parseVec3(const Params& p, const Key& k, const YAML::Node& n) {
  if (!n.IsSequence() || n.size() != 3) p.fail(k.name, describeNode(n), vectorExpected(k));
  Vec3 v;
  for (int i = 0; i < 3; ++i) {
    try {
      v[i] = n[i].as<double>();
    } catch (const YAML::Exception&) {
      p.fail(k.name, fmt::format("component {} = {}", i, describeNode(n[i])), vectorExpected(k));
    }
    if (!std::isfinite(v[i]) || !k.range.contains(v[i]))
      p.fail(k.name, fmt::format("component {} = {:g}", i, v[i]),
             fmt::format("components {} [{}]", k.range.describe(), k.unit));
  }
  return v;
}

std::string formatList(const std::vector<double>& values) {
  std::string s = "[";
  for (std::size_t i = 0; i < values.size(); ++i) s += (i ? ", " : "") + formatReal(values[i]);
  return s + "]";
}

/// A value for a required key in documentation mode, so that readers can go on.
double placeholderFor(const Range& r) {
  if (r.contains(1.0)) return 1.0;
  if (r.contains(r.min)) return r.min;
  if (!std::isinf(r.min) && !std::isinf(r.max)) return 0.5 * (r.min + r.max);
  if (!std::isinf(r.min)) return r.min + 1.0;
  return r.max - 1.0;
}

}  // namespace

double Params::real(const Key& k, double defaultValue) {
  const std::string text = formatReal(defaultValue);
  const YAML::Node* n = lookup(k, "real", &text, k.range.describe(), numberExpected(k));
  if (n == nullptr) return defaultValue;
  const double v = parseReal(*this, k, *n);
  record(k, formatReal(v), false);
  return v;
}

double Params::real(const Key& k) {
  const YAML::Node* n = lookup(k, "real", nullptr, k.range.describe(), numberExpected(k));
  if (n == nullptr) return placeholderFor(k.range);  // documentation mode
  const double v = parseReal(*this, k, *n);
  record(k, formatReal(v), false);
  return v;
}

long long Params::integer(const Key& k, long long defaultValue) {
  const std::string text = std::to_string(defaultValue);
  const YAML::Node* n = lookup(k, "integer", &text, k.range.describe(), "an integer");
  if (n == nullptr) return defaultValue;
  const long long v = parseInteger(*this, k, *n);
  record(k, std::to_string(v), false);
  return v;
}

long long Params::integer(const Key& k) {
  const YAML::Node* n = lookup(k, "integer", nullptr, k.range.describe(), "an integer");
  if (n == nullptr) return static_cast<long long>(placeholderFor(k.range));  // documentation mode
  const long long v = parseInteger(*this, k, *n);
  record(k, std::to_string(v), false);
  return v;
}

bool Params::boolean(const Key& k, bool defaultValue) {
  const std::string text = defaultValue ? "true" : "false";
  const YAML::Node* n = lookup(k, "boolean", &text, "true, false", "true or false");
  if (n == nullptr) return defaultValue;
  bool v = false;
  if (!n->IsScalar() || !YAML::convert<bool>::decode(*n, v)) fail(k.name, describeNode(*n), "true or false");
  record(k, v ? "true" : "false", false);
  return v;
}

std::string Params::text(const Key& k, const std::string& defaultValue) {
  const std::string text = defaultValue.empty() ? "\"\"" : defaultValue;
  const YAML::Node* n = lookup(k, "text", &text, "any text", "a text");
  if (n == nullptr) return defaultValue;
  if (!n->IsScalar()) fail(k.name, describeNode(*n), "a text");
  record(k, n->Scalar(), false);
  return n->Scalar();
}

std::string Params::text(const Key& k) {
  const YAML::Node* n = lookup(k, "text", nullptr, "any text", "a text");
  if (n == nullptr) return "placeholder";  // documentation mode
  if (!n->IsScalar() || n->Scalar().empty()) fail(k.name, describeNode(*n), "a non-empty text");
  record(k, n->Scalar(), false);
  return n->Scalar();
}

Vec3 Params::vec3(const Key& k, Vec3 defaultValue) {
  const std::string text = formatVec(defaultValue);
  const YAML::Node* n = lookup(k, "vector3", &text, k.range.describe(), vectorExpected(k));
  if (n == nullptr) return defaultValue;
  const Vec3 v = parseVec3(*this, k, *n);
  record(k, formatVec(v), false);
  return v;
}

Vec3 Params::vec3(const Key& k) {
  const YAML::Node* n = lookup(k, "vector3", nullptr, k.range.describe(), vectorExpected(k));
  if (n == nullptr) {  // documentation mode
    const double c = placeholderFor(k.range);
    return {c, c, c};
  }
  const Vec3 v = parseVec3(*this, k, *n);
  record(k, formatVec(v), false);
  return v;
}

std::vector<double> Params::reals(const Key& k, const std::vector<double>& defaultValue) {
  const std::string text = formatList(defaultValue);
  const YAML::Node* n = lookup(k, "list of reals", &text, k.range.describe(), listExpected(k));
  if (n == nullptr) return defaultValue;
  if (!n->IsSequence()) fail(k.name, describeNode(*n), listExpected(k));
  std::vector<double> out;
  for (std::size_t i = 0; i < n->size(); ++i) {
    double v = 0;
    try {
      v = (*n)[i].as<double>();
    } catch (const YAML::Exception&) {
      fail(k.name, fmt::format("item {} = {}", i, describeNode((*n)[i])), listExpected(k));
    }
    if (!std::isfinite(v) || !k.range.contains(v))
      fail(k.name, fmt::format("item {} = {:g}", i, v), fmt::format("values {} [{}]", k.range.describe(), k.unit));
    out.push_back(v);
  }
  record(k, formatList(out), false);
  return out;
}

std::string Params::readChoice(const Key& k, const std::vector<std::string>& allowed, const std::string* defaultValue) {
  const YAML::Node* n = lookup(k, "choice", defaultValue, joinNames(allowed), "one of: " + joinNames(allowed));
  if (n == nullptr) {
    if (defaultValue != nullptr) return *defaultValue;
    return allowed.empty() ? std::string() : allowed.front();  // documentation mode, required key
  }
  if (!n->IsScalar()) fail(k.name, describeNode(*n), "one of: " + joinNames(allowed));
  std::string v = n->Scalar();  // not const: returned by move
  if (std::find(allowed.begin(), allowed.end(), v) == allowed.end()) {
    const std::string suggestion = closestMatch(v, allowed);
    fail(k.name, fmt::format("'{}'{}", v, suggestion.empty() ? "" : fmt::format(" (did you mean '{}'?)", suggestion)),
         "one of: " + joinNames(allowed));
  }
  record(k, v, false);
  return v;
}

std::string Params::choice(const Key& k, const std::vector<std::string>& allowed, const std::string& defaultValue) {
  return readChoice(k, allowed, &defaultValue);
}

std::string Params::choice(const Key& k, const std::vector<std::string>& allowed) {
  return readChoice(k, allowed, nullptr);
}

// ---------------------------------------------------------------- nesting

Params Params::childParams(const YAML::Node& node, const std::string& childPrefix) {
  auto child = std::make_shared<Section>();
  child->node = node;
  child->prefix = childPrefix;
  return Params(shared_, child);
}

Params Params::section(const Key& k) {
  markQueried(k.name);
  if (documenting()) {
    document(k, "section", "optional", "map");
    return childParams(YAML::Node(), path(k.name));
  }
  const YAML::Node* n = find(k.name);
  if (n == nullptr || n->IsNull()) return childParams(YAML::Node(YAML::NodeType::Undefined), path(k.name));
  if (!n->IsMap()) fail(k.name, describeNode(*n), "a map of keys (section '" + std::string(k.name) + "')");
  return childParams(*n, path(k.name));
}

Params Params::requiredSection(const Key& k) {
  if (documenting()) document(k, "section", "required", "map");
  if (!documenting() && !has(k.name)) {
    markQueried(k.name);
    fail(k.name, "nothing", "a map of keys (this section is required)");
  }
  return section(k);
}

std::vector<Params> Params::list(const Key& k) {
  markQueried(k.name);
  if (documenting()) {
    document(k, "list", "[]", "list of maps");
    return {childParams(YAML::Node(), path(k.name) + "[]")};
  }
  const YAML::Node* n = find(k.name);
  std::vector<Params> out;
  if (n == nullptr || n->IsNull()) return out;
  if (!n->IsSequence()) fail(k.name, describeNode(*n), "a list of maps (each item starting with '- ')");
  const YAML::Node seq = *n;
  for (std::size_t i = 0; i < seq.size(); ++i) {
    const YAML::Node item = seq[i];
    const std::string itemPath = fmt::format("{}[{}]", path(k.name), i);
    if (!item.IsMap()) throw CaseError(locationOf(shared_->file, item), itemPath, describeNode(item), "a map of keys");
    out.push_back(childParams(item, itemPath));
  }
  return out;
}

// ---------------------------------------------------------------- checks and reports

void Params::checkUnknownKeys() const {
  if (documenting()) return;
  for (const auto& section : shared_->sections) {
    const YAML::Node& map = section->node;
    if (!map.IsDefined() || !map.IsMap()) continue;
    for (auto it = map.begin(); it != map.end(); ++it) {
      const std::string key = it->first.Scalar();
      if (section->queried->count(key)) continue;
      std::vector<std::string> valid(section->queried->begin(), section->queried->end());
      const std::string suggestion = closestMatch(key, valid);
      const std::string where = section->prefix.empty() ? key : section->prefix + "." + key;
      throw CaseError(locationOf(shared_->file, it->first), where,
                      fmt::format("an unknown key '{}'{}", key,
                                  suggestion.empty() ? "" : fmt::format(" (did you mean '{}'?)", suggestion)),
                      "one of: " + joinNames(valid));
    }
  }
}

std::vector<ResolvedKey> Params::resolved() const { return shared_->resolved; }
namespace {
/// Which models declare a key, from the model stacks of its declarations: for each choice, the
/// models that declare it, unless that is every model of the choice (or the key is also declared
/// outside the choice). "type = lattice, rate"; "all types" where every model of the choices declares
/// it; empty for a key no model declares.
template <class Stacks, class Choices>
std::string declaringModels(const Stacks& declarations, const Choices& choices) {
  std::vector<std::string> order;  // choice paths, outermost first
  std::map<std::string, std::set<std::string>> models;
  std::map<std::string, std::size_t> count;  // declarations inside each choice
  for (const auto& stack : declarations)
    for (const auto& frame : stack) {
      if (!models.count(frame.choicePath)) order.push_back(frame.choicePath);
      models[frame.choicePath].insert(frame.model);
      ++count[frame.choicePath];
    }
  if (order.empty()) return "";
  std::vector<std::string> parts;
  for (const std::string& choicePath : order) {
    const auto& choice = choices.at(choicePath);
    const bool everyModel = models[choicePath].size() == choice.models.size() && choice.models.size() > 1;
    if (everyModel || count[choicePath] < declarations.size()) continue;
    std::vector<std::string> names;
    for (const std::string& m : choice.models)  // (the registry's order)
      if (models[choicePath].count(m)) names.push_back(m);
    parts.push_back(choice.key + " = " + joinNames(names));
  }
  if (parts.empty()) return "all " + choices.at(order.back()).key + "s";
  std::string out = parts.front();
  for (std::size_t i = 1; i < parts.size(); ++i) out += "; " + parts[i];
  return out;
}

/// The default of a key whose models give it different defaults: each value with the models (of
/// the innermost choice) that use it, "0.001 (log_normal), 0.002 (rosin_rammler)"; else the first
/// declaration's default (also for a key declared outside any model: a section read again).
template <class Declared>
std::string defaultsByModel(const Declared& declared) {
  for (const auto& stack : declared.stacks)
    if (stack.empty()) return declared.defaults.front();
  std::vector<std::string> values;
  std::map<std::string, std::vector<std::string>> models;
  for (std::size_t d = 0; d < declared.defaults.size(); ++d) {
    const std::string& value = declared.defaults[d];
    if (!models.count(value)) values.push_back(value);
    auto& names = models[value];
    const std::string model = declared.stacks[d].empty() ? "" : declared.stacks[d].back().model;
    if (!model.empty() && std::find(names.begin(), names.end(), model) == names.end()) names.push_back(model);
  }
  if (values.size() == 1) return values.front();
  std::string out;
  for (const std::string& value : values)
    out += fmt::format("{}{} ({})", out.empty() ? "" : ", ", value.empty() ? "required" : value, joinNames(models[value]));
  return out;
}
}  // namespace

std::vector<KeyDoc> Params::documentedKeys() const {
  std::vector<KeyDoc> out = shared_->docs;
  for (KeyDoc& k : out) {
    const Shared::Declarations& declared = shared_->declarations.at(k.path);
    k.help.clear();
    for (const std::string& help : declared.helps)
      if (!help.empty()) k.help += (k.help.empty() ? "" : "; ") + help;
    const std::string models = declaringModels(declared.stacks, shared_->choices);
    if (!models.empty()) k.help = "(" + models + ") " + k.help;
    k.defaultValue = defaultsByModel(declared);
  }
  return out;
}

}  // namespace gf
