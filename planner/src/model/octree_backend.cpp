#include "octomotion/planner/model/octree_backend.h"

namespace octomotion {

OctreeBackend::OctreeBackend(std::shared_ptr<const OctreeCollisionModel> model, CheckerPath path)
    : model_(std::move(model)), path_(path) {
  if (!model_) throw InvalidArgument("OctreeBackend: no model");
}

std::unique_ptr<BackendScratch> OctreeBackend::makeBackendScratch() const {
  auto scratch = std::make_unique<Scratch>();
  scratch->check = model_->makeScratch();
  scratch->owner = model_->id();
  return scratch;
}

const char* OctreeBackend::name() const {
  return path_ == CheckerPath::kFused ? "octree-fused" : "octree";
}

void OctreeBackend::throwForeignScratch() {
  throw InvalidArgument("OctreeBackend: the scratch was made by another backend");
}

}  // namespace octomotion
