#pragma once
// Case-file reader and schema in one place (the Lethe habit: every parameter is declared
// where it is read, with its default, SI unit, range and help text).
//
//   Params p = Params::loadFile("case.yaml");
//   Params time = p.section({"time", "", "time stepping"});
//   double dt = time.real({"dem_step", "s", "DEM time step", Range::positive()});
//   ...
//   p.checkUnknownKeys();   // unknown keys anywhere -> CaseError with "did you mean"
//
// The same reading code, run on Params::documentation(), records every key instead of
// reading values: docs/case-file.md and `grainflow check` come from it, so code, checks and
// documentation cannot drift apart.
#include <limits>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.hpp"
#include "core/vec3.hpp"

namespace YAML {
class Node;
}

namespace gf {

/// Allowed range of a numeric key.
struct Range {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool minInclusive = true;
  bool maxInclusive = true;

  static Range any() { return {}; }
  static Range positive() { return {0.0, std::numeric_limits<double>::infinity(), false, true}; }
  static Range nonNegative() { return {0.0, std::numeric_limits<double>::infinity(), true, true}; }
  static Range atLeast(double a) { return {a, std::numeric_limits<double>::infinity(), true, true}; }
  static Range between(double a, double b) { return {a, b, true, true}; }
  static Range above(double a) { return {a, std::numeric_limits<double>::infinity(), false, true}; }

  bool contains(double v) const;
  bool unrestricted() const;
  std::string describe() const;  // "> 0", "in [0, 1]", "any"
};

/// Declaration of one case-file key.
struct Key {
  std::string_view name;
  std::string_view unit = "-";
  std::string_view help = "";
  Range range = {};
};

/// One declared key, for documentation.
struct KeyDoc {
  std::string path;          // e.g. "walls[].normal"
  std::string type;          // real, integer, boolean, text, vector3, choice, section, list
  std::string defaultValue;  // empty = required
  std::string unit;
  std::string allowed;       // range or list of names
  std::string help;
};

/// One key as read from a case (default filled in where the file had none).
struct ResolvedKey {
  std::string path;
  std::string value;
  std::string unit;
  bool fromDefault = false;
};

class Params {
 public:
  /// Reads and parses a YAML case file. Missing, unreadable, empty, not-YAML and
  /// not-a-map files throw CaseError naming the file (and line/column where known).
  static Params loadFile(const std::string& path);
  static Params loadString(const std::string& yamlText, const std::string& displayName);
  /// A reader that records declarations and returns defaults (or in-range placeholders).
  static Params documentation();

  ~Params();
  Params(const Params&);
  Params& operator=(const Params&);
  Params(Params&&) noexcept;
  Params& operator=(Params&&) noexcept;

  double real(const Key& k, double defaultValue);
  double real(const Key& k);
  long long integer(const Key& k, long long defaultValue);
  long long integer(const Key& k);
  bool boolean(const Key& k, bool defaultValue);
  std::string text(const Key& k, const std::string& defaultValue);
  std::string text(const Key& k);
  Vec3 vec3(const Key& k, Vec3 defaultValue);
  Vec3 vec3(const Key& k);
  std::vector<double> reals(const Key& k, const std::vector<double>& defaultValue);
  /// One name out of `allowed` (e.g. the registered models of a kind).
  std::string choice(const Key& k, const std::vector<std::string>& allowed, const std::string& defaultValue);
  std::string choice(const Key& k, const std::vector<std::string>& allowed);

  /// A nested map. Absent -> an empty section (all its keys take defaults).
  Params section(const Key& k);
  /// A required nested map.
  Params requiredSection(const Key& k);
  /// A sequence of maps. Absent -> empty.
  std::vector<Params> list(const Key& k);

  bool has(std::string_view key) const;
  /// Whether the key is present and a sequence (keys that take either a word or a list).
  bool isSequence(std::string_view key) const;
  /// Whether the key is present and is the word `word` (keys that take either a number or a word).
  bool isWord(std::string_view key, std::string_view word) const;
  bool documenting() const;
  /// In documentation mode, the keys declared until the matching endModelDocumentation() belong to
  /// model `model` of the choice `choiceKey` of this section, one of `models` (the registry calls
  /// these around each model's reader; calls nest). documentedKeys() then says in each key's help
  /// which models declare it: "(type = lattice)", "(type = lattice, rate)", or "(all types)".
  void beginModelDocumentation(std::string_view choiceKey, const std::vector<std::string>& models,
                               const std::string& model);
  void endModelDocumentation();
  /// Full dotted path of a key in this section, e.g. "walls[1].normal".
  std::string path(std::string_view key) const;
  /// Where a key (or, when absent, this section) stands in the file.
  FileLocation location(std::string_view key) const;
  const std::string& fileName() const;

  /// Throws CaseError for `key` of this section with the given found/expected texts.
  [[noreturn]] void fail(std::string_view key, const std::string& found, const std::string& expected) const;

  /// Throws CaseError for the first key in the whole tree read so far that no reader asked
  /// for, suggesting the closest valid key.
  void checkUnknownKeys() const;

  std::vector<ResolvedKey> resolved() const;
  /// Every declared key, in the order of first declaration; a key that models of a choice declare
  /// starts its help with the models that declare it (see beginModelDocumentation).
  std::vector<KeyDoc> documentedKeys() const;

 private:
  struct Shared;
  struct Section;
  Params(std::shared_ptr<Shared> shared, std::shared_ptr<Section> section);
  Params childParams(const YAML::Node& node, const std::string& childPrefix);
  const YAML::Node* find(std::string_view key) const;
  /// Common path of the value readers: marks the key as known; in documentation mode documents it
  /// and returns nullptr; otherwise returns the key's node, or records the default and returns
  /// nullptr, or (no default given) fails naming what was expected.
  const YAML::Node* lookup(const Key& k, const char* type, const std::string* defaultText, const std::string& allowed,
                           const std::string& expected) const;
  std::string readChoice(const Key& k, const std::vector<std::string>& allowed, const std::string* defaultValue);
  void markQueried(std::string_view key) const;
  void document(const Key& k, std::string type, std::string defaultValue, std::string allowed) const;
  void record(const Key& k, std::string value, bool fromDefault) const;

  std::shared_ptr<Shared> shared_;
  std::shared_ptr<Section> section_;
};

/// Edit distance, for "did you mean" suggestions.
std::size_t editDistance(std::string_view a, std::string_view b);
/// The closest candidate within a small edit distance, or "" if none is close.
std::string closestMatch(std::string_view word, const std::vector<std::string>& candidates);

}  // namespace gf
