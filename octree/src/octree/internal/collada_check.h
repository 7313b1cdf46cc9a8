// Structural validation of a COLLADA file before assimp reads it (collada_check.cpp).
#pragma once

#include <string>

namespace octomotion::detail {

// Throws FileError(path, ...) naming the element and its line unless `text` is a COLLADA
// document whose mesh data assimp 5.2's importer reads within bounds: well-formed elements,
// arrays whose `count` matches their content, accessors reading inside their array, inputs
// naming a source of the right kind, primitive index lists whose counts agree and whose
// indices are in range, no instance_node cycle, and only the primitive kinds robot meshes use
// (triangles, polylist, polygons without holes, lines, linestrips); skins, morphs and
// animations are refused.
void validateCollada(const std::string& text, const std::string& path);

}  // namespace octomotion::detail
