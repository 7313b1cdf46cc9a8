#include "commands.h"
#include "octomotion/error.h"

namespace octomotion::cli {

int benchCommand(const std::vector<std::string>& /*args*/) {
  throw Error("octomotion bench: not available in this build yet");
}

}  // namespace octomotion::cli
