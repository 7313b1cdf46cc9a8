// COLLADA files are validated before assimp reads them (octree/src/octree/collada_check.cpp):
// each structural defect of a valid tetrahedron is refused with a FileError naming the file and
// the element, the unmodified file and the robot-mesh features the validator whitelists still
// load, and the regression files the fuzzer found are refused.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <unistd.h>

#include <Eigen/Geometry>

#include "octomotion/error.h"
#include "octomotion/octree/mesh.h"

namespace octomotion {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

std::string readText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string tetraText() {
  return readText(std::string(OCTOMOTION_TEST_DATA_DIR) + "/meshes/tetra_cm_zup.dae");
}

class ColladaStructure : public ::testing::Test {
 protected:
  std::string write(const std::string& name, const std::string& text) {
    const fs::path dir =
        fs::temp_directory_path() / ("octomotion_collada_structure_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const std::string path = (dir / name).string();
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }

  // The tetrahedron with `from` replaced by `to` (which must occur).
  std::string mutated(const std::string& from, const std::string& to) {
    std::string text = tetraText();
    const std::size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
    return text;
  }

  void expectRefused(const std::string& name, const std::string& text, const std::string& says) {
    const std::string path = write(name, text);
    try {
      loadMesh(path);
      ADD_FAILURE() << name << " was accepted";
    } catch (const FileError& e) {
      EXPECT_THAT(e.what(), HasSubstr(name)) << "the message must name the file";
      EXPECT_THAT(e.what(), HasSubstr(says)) << name;
    } catch (const std::exception& e) {
      ADD_FAILURE() << name << ": not a FileError: " << e.what();
    }
  }
};

TEST_F(ColladaStructure, TheUnmodifiedFileLoads) {
  const TriangleMesh mesh = loadMesh(write("tetra.dae", tetraText()));
  EXPECT_EQ(mesh.vertices.size(), 4u);
  EXPECT_EQ(mesh.triangles.size(), 4u);
}

TEST_F(ColladaStructure, ABlenderStyleFileLoads) {
  // Normals and texture coordinates on their own index offsets, effects, an empty
  // <library_controllers/>: what exporters write for robot meshes.
  MeshLoadOptions raw;  // the file's own coordinates (metres, Z up)
  raw.keep_root_transform = false;
  const TriangleMesh mesh =
      loadMesh(std::string(OCTOMOTION_TEST_DATA_DIR) + "/meshes/blender_style_tetra.dae", raw);
  EXPECT_EQ(mesh.triangles.size(), 4u);
  EXPECT_TRUE(isClosedManifold(mesh));
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& v : mesh.vertices) box.extend(v);
  EXPECT_NEAR(box.max().maxCoeff(), 0.1, 1e-6);  // assimp reads floats
  EXPECT_NEAR(box.min().minCoeff(), 0.0, 1e-6);
}

TEST_F(ColladaStructure, WhitelistedPrimitivesLoad) {
  // The same four faces as a polylist, as polygons, and with an unused lines primitive.
  const std::string p = "<p>0 2 1  0 1 3  0 3 2  1 2 3</p>";
  const std::string input = R"(<input semantic="VERTEX" source="#tetra-vtx" offset="0"/>)";
  const std::string triangles_block =
      "<triangles count=\"4\">\n          " + input + "\n          " + p + "\n        </triangles>";
  std::string text = tetraText();
  ASSERT_NE(text.find(triangles_block), std::string::npos);
  for (const std::string& replacement :
       {"<polylist count=\"4\">" + input + "<vcount>3 3 3 3</vcount>" + p + "</polylist>",
        "<polygons count=\"4\">" + input + "<p>0 2 1</p><p>0 1 3</p><p>0 3 2</p><p>1 2 3</p>" +
            "</polygons>",
        triangles_block + "<lines count=\"2\">" + input + "<p>0 1 2 3</p></lines>"}) {
    std::string variant = text;
    variant.replace(variant.find(triangles_block), triangles_block.size(), replacement);
    const TriangleMesh mesh = loadMesh(write("variant.dae", variant));
    EXPECT_EQ(mesh.triangles.size(), 4u) << replacement;
  }
}

TEST_F(ColladaStructure, ArraysMustHoldTheirCount) {
  expectRefused("no_count.dae", mutated(R"( count="12">0 0 0)", ">0 0 0"),
                "<float_array> (line 12) has no count attribute");
  expectRefused("short_count.dae", mutated(R"(count="12")", R"(count="13")"),
                "has count=\"13\" but holds 12 values");
  expectRefused("bad_count.dae", mutated(R"(count="12")", R"(count="-1")"),
                "count=\"-1\" is not an integer");
  expectRefused("word.dae", mutated("0 0 0 10 0 0", "0 0 0 ten 0 0"), "not a decimal number");
  expectRefused("hex.dae", mutated("0 0 0 10 0 0", "0 0 0 0x1p3 0 0"), "not a decimal number");
}

TEST_F(ColladaStructure, AccessorsMustReadInsideTheirArray) {
  expectRefused("accessor_count.dae", mutated(R"(count="4" stride="3")", R"(count="5" stride="3")"),
                "<accessor> (line 14) reads 15 values of an array of 12");
  expectRefused("accessor_stride.dae", mutated(R"(stride="3")", R"(stride="0")"), "stride 0");
  expectRefused("accessor_params.dae",
                mutated(R"(count="4" stride="3")", R"(count="4" stride="2")"),
                "more <param> than its stride");
  expectRefused("accessor_no_count.dae", mutated(R"(count="4" stride="3")", R"(stride="3")"),
                "<accessor> (line 14) has no count attribute");
}

TEST_F(ColladaStructure, IndicesMustBeInRangeAndCounted) {
  expectRefused("index_range.dae", mutated("1 2 3</p>", "1 2 4</p>"),
                "<p> (line 26) index 4 is out of range (4 items)");
  expectRefused("triangle_count.dae",
                mutated(R"(<triangles count="4">)", R"(<triangles count="5">)"),
                "has count=\"5\" but indexes 12 vertices");
  expectRefused("offset.dae", mutated(R"(offset="0")", R"(offset="65")"), "offset=\"65\"");
  expectRefused("vertex_kind.dae",
                mutated(R"(source="#tetra-vtx" offset="0")", R"(source="#tetra-pos" offset="0")"),
                "VERTEX names <source>");
  expectRefused("no_position.dae", mutated(R"(semantic="POSITION")", R"(semantic="NORMAL")"),
                "<vertices> (line 21) has no POSITION input");
}

TEST_F(ColladaStructure, UnsupportedOrMalformedStructureIsRefused) {
  expectRefused("strips.dae", mutated(R"(<triangles count="4">)", R"(<tristrips count="4">)"),
                "does not match");
  std::string strips = mutated(R"(<triangles count="4">)", R"(<tristrips count="4">)");
  strips.replace(strips.find("</triangles>"), 12, "</tristrips>");
  expectRefused("strips2.dae", strips, "<tristrips> (line 24) is not supported");
  expectRefused("cdata.dae", mutated("<up_axis>", "<up_axis><![CDATA[Z_UP]]>"), "CDATA");
  // pugixml reads only the text before a comment: the two readings would differ.
  expectRefused("split.dae", mutated("0 1 3  0 3 2", "0 1 3<!-- -->0 3 2"),
                "<p> (line 26) holds markup inside its values");
  expectRefused("self_instance.dae",
                mutated(R"(<instance_geometry url="#tetra"/>)",
                        R"(<instance_geometry url="#tetra"/><instance_node url="#tetra-node"/>)"),
                "instances itself");
  expectRefused("geometry_kind.dae", mutated(R"(url="#tetra")", R"(url="#tetra-pos")"),
                "does not name a <geometry>");
  expectRefused("geometry_url.dae", mutated(R"(url="#tetra")", R"(url="#nothing")"),
                "<instance_geometry> (line 34) does not name an element");
  expectRefused("duplicate_id.dae", mutated(R"(id="tetra" name)", R"(id="tetra-pos" name)"),
                "repeats the id \"tetra-pos\"");
}

TEST_F(ColladaStructure, LongInstanceChainsAreRefused) {
  // 100 library nodes, each instancing the next: no cycle, but assimp recurses once per link.
  std::string nodes = "<library_nodes>";
  for (int i = 0; i < 100; ++i) {
    nodes += "<node id=\"n" + std::to_string(i) + "\">";
    if (i + 1 < 100) nodes += "<instance_node url=\"#n" + std::to_string(i + 1) + "\"/>";
    nodes += "</node>";
  }
  nodes += "</library_nodes>";
  expectRefused("chain.dae", mutated("<library_visual_scenes>", nodes + "<library_visual_scenes>"),
                "chain of more than 64 <instance_node>");
}

TEST_F(ColladaStructure, FuzzerFindingsAreRefused) {
  // The input that crashed assimp 5.2's importer (a <float_array> without count).
  const std::string path = std::string(OCTOMOTION_TEST_DATA_DIR) + "/bad/collada_no_count.dae";
  try {
    loadMesh(path);
    ADD_FAILURE() << "accepted";
  } catch (const FileError& e) {
    EXPECT_THAT(e.what(), HasSubstr("collada_no_count.dae"));
    EXPECT_THAT(e.what(), HasSubstr("<float_array>"));
  }
}

TEST_F(ColladaStructure, FilesAssimpWouldReadAsColladaAreAllValidated) {
  // The fuzzer's out-of-memory input: junk before the XML made the pre-scan take the file for
  // something else, and assimp's parser skipped the junk and read it as Collada unchecked.
  const std::string junk = std::string(OCTOMOTION_TEST_DATA_DIR) + "/bad/collada_junk_head.dae";
  try {
    loadMesh(junk);
    ADD_FAILURE() << "accepted";
  } catch (const FileError& e) {
    EXPECT_THAT(e.what(), HasSubstr("collada_junk_head.dae"));
    EXPECT_THAT(e.what(), HasSubstr("must start with an XML element"));
  }
  // Whatever the extension, a file with "<COLLADA" near its start is validated.
  expectRefused("disguised.mesh", "junk" + mutated(R"(count="12")", R"(count="13")"),
                "must start with an XML element");
  expectRefused("disguised.xml", mutated(R"(count="12")", R"(count="13")"),
                "has count=\"13\" but holds 12 values");
  expectRefused("zipped.zae", tetraText(), "zipped COLLADA (.zae) is not supported");
}

}  // namespace
}  // namespace octomotion
