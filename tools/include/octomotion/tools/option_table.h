// Command-line options as tables: each flag is a name, the kind of value it takes (its
// placeholder in the help, or none for a switch), its help and a setter. The octomotion command
// (plan, check, info, view, bench) and bench/tradeoff_bench parse with the same tables, so a
// flag means the same everywhere and the help is generated from what is parsed.
#pragma once

#include <algorithm>
#include <cstddef>
#include <functional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "octomotion/planner/ompl/planning_scene.h"

namespace octomotion::tools {

template <class Target>
struct Option {
  const char* name;   // "--states"
  const char* value;  // the value's placeholder in the help ("N", "on|off"); nullptr: a switch
  const char* help;   // lines after the first start with '\n'; nullptr: not in the help
  // Sets the flag's value (empty for a switch) in the target; throws InvalidArgument naming the
  // flag for a bad value.
  std::function<void(const std::string& flag, const std::string& value, Target& target)> set;
};

template <class Target>
class OptionTable {
 public:
  explicit OptionTable(std::vector<Option<Target>> options) : options_(std::move(options)) {}

  // The options of `other`, applied to the part of Target that `part` selects; those named in
  // `unlisted` are parsed but left out of the help.
  template <class Part, class Select>
  void append(const OptionTable<Part>& other, Select part,
              const std::vector<std::string>& unlisted = {}) {
    for (const Option<Part>& o : other.options()) {
      const bool listed = std::find(unlisted.begin(), unlisted.end(), o.name) == unlisted.end();
      options_.push_back({o.name, o.value, listed ? o.help : nullptr,
                          [set = o.set, part](const std::string& flag, const std::string& value,
                                              Target& target) { set(flag, value, part(target)); }});
    }
  }

  // Applies `arg` when it is one of the options (reading its value through `value`, which throws
  // when it is missing); false otherwise.
  bool parse(const std::string& arg, const std::function<std::string()>& value,
             Target& target) const {
    for (const Option<Target>& o : options_) {
      if (arg != o.name) continue;
      o.set(arg, o.value ? value() : std::string(), target);
      return true;
    }
    return false;
  }

  // One entry per option: "  --name VALUE" then the help in a column.
  void writeHelp(std::ostream& out) const {
    constexpr std::size_t kHelpColumn = 27;
    for (const Option<Target>& o : options_) {
      if (!o.help) continue;
      std::string left = std::string("  ") + o.name;
      if (o.value) left += std::string(" ") + o.value;
      if (left.size() < kHelpColumn) {
        left.resize(kHelpColumn, ' ');
      } else if (left.size() <= kHelpColumn + 2) {
        left += "  ";
      } else {
        left += "\n" + std::string(kHelpColumn, ' ');
      }
      out << left;
      for (const char* c = o.help; *c; ++c) {
        out << *c;
        if (*c == '\n') out << std::string(kHelpColumn, ' ');
      }
      out << '\n';
    }
  }

  const std::vector<Option<Target>>& options() const { return options_; }

 private:
  std::vector<Option<Target>> options_;
};

// The value after the flag args[i]: advances i past it, or throws InvalidArgument naming the
// flag when the arguments end first. Commands wrap it as their options' `value` callback.
std::string flagValue(const std::vector<std::string>& args, std::size_t& i);

// Values. Each throws InvalidArgument naming the flag.
double parseNumber(const std::string& flag, const std::string& value);      // finite
std::size_t parseCount(const std::string& flag, const std::string& value);  // whole, <= 1e9
bool parseOnOff(const std::string& flag, const std::string& value);
std::vector<std::string> parseList(const std::string& flag, const std::string& value);  // A,B,...

// The scene options every command shares (--resolution, --rounding, --checker, --planner,
// --time, --seed, --package-path and the octree settings): SceneOverrides.
const OptionTable<SceneOverrides>& sceneOptions();

}  // namespace octomotion::tools
