#include "commands.h"
#include "octomotion/error.h"

namespace octomotion::cli {

int viewCommand(const std::vector<std::string>& /*args*/) {
  throw Error("octomotion view: not available in this build yet");
}

}  // namespace octomotion::cli
