#include "octomotion/tools/experiment_name.h"

#include <cctype>
#include <string>

#include "octomotion/tools/trade_study.h"

namespace octomotion {
namespace {

std::string oneWord(const std::string& s) {
  std::string out = s;
  for (char& c : out) {
    const unsigned char u = static_cast<unsigned char>(c);
    if (!std::isalnum(u) && c != '.' && c != '_' && c != '-') c = '-';
  }
  return out.empty() ? "-" : out;
}

}  // namespace

std::string experimentName(const std::string& scene, const std::string& checker, double resolution,
                           const std::string& rounding) {
  std::string name = oneWord(scene) + "_" + oneWord(checker);
  if (resolution > 0) {
    std::string label = resolutionLabel(resolution);  // "2 cm": the space goes
    label.erase(label.find(' '), 1);
    name += "_" + oneWord(label);
  }
  if (!rounding.empty()) name += "_" + oneWord(rounding);
  return name;
}

}  // namespace octomotion
