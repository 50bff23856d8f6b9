#pragma once
// Run-time selection of models by name (OpenFOAM's run-time selection tables, LAMMPS styles).
//
// A model is one file: it implements an interface and registers a factory by name:
//
//   GF_REGISTER_MODEL(DragLaw, DiFeliceDrag, "di_felice", "Di Felice (1994) voidage function");
//
// The case file names the model ("model: di_felice"); Registry<DragLaw>::create(section)
// reads that key, lists the registered names on a typo, and hands the section to the factory,
// which reads the model's own keys. Interfaces work on whole arrays (one virtual call per
// time step, never per particle) or are dispatched once into templated kernels.
#include <algorithm>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/params.hpp"

namespace gf {

template <class Interface>
class Registry {
 public:
  using Factory = std::function<std::unique_ptr<Interface>(Params&)>;
  struct Entry {
    std::string help;
    Factory make;
  };

  static Registry& instance() {
    static Registry registry;
    return registry;
  }

  bool add(const std::string& name, const std::string& help, Factory factory) {
    entries_[name] = Entry{help, std::move(factory)};
    return true;
  }

  std::vector<std::string> names() const {
    std::vector<std::string> out;
    for (const auto& [name, entry] : entries_) out.push_back(name);
    return out;
  }

  bool contains(const std::string& name) const { return entries_.count(name) > 0; }
  const std::map<std::string, Entry>& entries() const { return entries_; }

  /// Reads `modelKey` from `section` (one of the registered names) and builds that model
  /// from the same section. In documentation mode every registered model documents its keys.
  std::unique_ptr<Interface> create(Params& section, const Key& modelKey, const std::string& defaultName = "",
                                    std::string* chosenName = nullptr) {
    const std::vector<std::string> valid = names();
    if (section.documenting()) {
      section.choice(modelKey, valid, defaultName);
      std::unique_ptr<Interface> first;
      for (const auto& [name, entry] : entries_) {
        section.beginModelDocumentation(modelKey.name, valid, name);
        auto made = entry.make(section);
        section.endModelDocumentation();
        if (!first) first = std::move(made);
      }
      return first;
    }
    const std::string name =
        defaultName.empty() ? section.choice(modelKey, valid) : section.choice(modelKey, valid, defaultName);
    if (chosenName != nullptr) *chosenName = name;
    return entries_.at(name).make(section);
  }

  std::unique_ptr<Interface> createByName(const std::string& name, Params& section) {
    return entries_.at(name).make(section);
  }

 private:
  std::map<std::string, Entry> entries_;
};

}  // namespace gf

#define GF_CONCAT_INNER(a, b) a##b
#define GF_CONCAT(a, b) GF_CONCAT_INNER(a, b)
/// Registers `Class` (constructible from Params&) as model `name` of interface `Interface`.
#define GF_REGISTER_MODEL(Interface, Class, name, help)                                                   \
  namespace {                                                                                           \
  [[maybe_unused]] const bool GF_CONCAT(gfRegistered_, __LINE__) = ::gf::Registry<Interface>::instance().add( \
      name, help, [](::gf::Params& p) -> std::unique_ptr<Interface> { return std::make_unique<Class>(p); }); \
  }
