#include "octomotion/error.h"

#include <iostream>

namespace octomotion {

void warn(const WarningSink& sink, const std::string& message) {
  if (sink) {
    sink(message);
  } else {
    std::cerr << "octomotion: warning: " << message << "\n";
  }
}

}  // namespace octomotion
