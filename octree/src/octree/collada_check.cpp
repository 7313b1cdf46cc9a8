// assimp 5.2's Collada importer trusts the file: a `count` sizes buffers that the content then
// over- or under-fills, an accessor reads wherever its offset and stride point, an index is used
// without a range check, and an instance_node cycle recurses without end (fuzz/known/README.md).
// So the file is parsed here first, into a light element tree, and refused unless every piece
// of mesh data assimp will touch is consistent. What robot meshes use is accepted; the rest is
// refused rather than guessed at.
#include "internal/collada_check.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <map>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

#include "octomotion/error.h"

namespace octomotion::detail {
namespace {

// Counts and indices above this are refused: assimp stores them in 32-bit fields, and no mesh
// that fits the file size limit needs more.
constexpr std::uint64_t kMaxCount = std::uint64_t{1} << 31;
// An input's offset sets the index stride of its primitive; real files use a handful.
constexpr std::uint64_t kMaxInputOffset = 64;
// assimp keeps at most 8 texture coordinate and colour sets.
constexpr std::uint64_t kMaxInputSet = 7;
// Nodes instanced through nodes: assimp recurses once per level.
constexpr std::size_t kMaxInstanceChain = 64;

struct Element {
  std::string name;
  std::vector<std::pair<std::string, std::string>> attributes;
  std::string text;  // kept only for the elements whose content is checked
  std::size_t line = 0;
  int parent = -1;
  std::vector<int> children;

  const std::string* attribute(const char* key) const {
    for (const auto& [k, v] : attributes) {
      if (k == key) return &v;
    }
    return nullptr;
  }
};

bool isArray(const std::string& name) {
  return name == "float_array" || name == "int_array" || name == "Name_array" ||
         name == "IDREF_array" || name == "bool_array" || name == "SIDREF_array";
}

bool keepsText(const std::string& name) {
  return isArray(name) || name == "p" || name == "vcount";
}

bool isPrimitive(const std::string& name) {
  return name == "triangles" || name == "polylist" || name == "polygons" || name == "lines" ||
         name == "linestrips";
}

// Elements assimp's importer supports but robot meshes never contain, where its reader trusts
// the file the most (skins, morphs, animation channels, triangle strips and fans, holes).
bool isRefused(const std::string& name) {
  return name == "controller" || name == "skin" || name == "morph" || name == "animation" ||
         name == "animation_clip" || name == "tristrips" || name == "trifans" || name == "ph" ||
         name == "h";
}

std::string printable(const std::string& s) {
  std::string out = s.substr(0, 64);
  for (char& c : out) {
    if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) > 0x7e) c = '?';
  }
  return out;
}

class Checker {
 public:
  Checker(const std::string& text, const std::string& path) : text_(text), path_(path) {}

  void run() {
    parse();
    indexIds();
    // Arrays first (their counts are used by every accessor), then everything an element
    // refers to, then the primitives that index through inputs and accessors.
    for (std::size_t i = 0; i < elements_.size(); ++i) {
      if (isArray(elements_[i].name)) array_counts_[static_cast<int>(i)] = arrayCount(elements_[i]);
    }
    for (std::size_t i = 0; i < elements_.size(); ++i) checkElement(static_cast<int>(i));
    for (const Element& e : elements_) {
      if (isPrimitive(e.name)) checkPrimitive(e);
    }
    checkInstanceNodes();
  }

 private:
  [[noreturn]] void fail(const Element& e, const std::string& what) const {
    throw FileError(path_,
                    "<" + printable(e.name) + "> (line " + std::to_string(e.line) + ") " + what);
  }
  [[noreturn]] void failAt(std::size_t at, const std::string& what) const {
    throw FileError(path_, "line " + std::to_string(lineOf(at)) + ": " + what);
  }

  std::size_t lineOf(std::size_t at) {
    // Lines are counted incrementally: the parser only moves forward.
    at = std::min(at, text_.size());
    if (at < line_pos_) {
      line_pos_ = 0;
      line_ = 1;
    }
    line_ +=
        static_cast<std::size_t>(std::count(text_.begin() + static_cast<std::ptrdiff_t>(line_pos_),
                                            text_.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
    line_pos_ = at;
    return line_;
  }
  std::size_t lineOf(std::size_t at) const {
    return 1 + static_cast<std::size_t>(std::count(
                   text_.begin(), text_.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
  }

  static bool isNameChar(char c) {
    const unsigned char u = static_cast<unsigned char>(c);
    return std::isalnum(u) || c == '_' || c == '-' || c == '.' || c == ':' || u >= 0x80;
  }

  // A light XML reader: elements, attributes and text; comments and the declaration skipped;
  // DOCTYPE and CDATA refused (robot meshes use neither, and CDATA would hide content from the
  // checks below).
  void parse() {
    std::vector<int> open;
    std::size_t i = 0;
    const std::size_t n = text_.size();
    while (i < n) {
      const std::size_t lt = text_.find('<', i);
      const std::size_t text_end = lt == std::string::npos ? n : lt;
      if (!open.empty() && keepsText(elements_[static_cast<std::size_t>(open.back())].name)) {
        elements_[static_cast<std::size_t>(open.back())].text.append(text_, i, text_end - i);
      }
      if (lt == std::string::npos) break;
      // pugixml (assimp's parser) gives only the first run of text of an element that a comment,
      // instruction or child splits: such content is refused rather than read two ways.
      const bool in_text_element =
          !open.empty() && keepsText(elements_[static_cast<std::size_t>(open.back())].name);
      if (in_text_element && text_.compare(lt, 2, "</") != 0) {
        fail(elements_[static_cast<std::size_t>(open.back())], "holds markup inside its values");
      }
      if (text_.compare(lt, 4, "<!--") == 0) {
        const std::size_t end = text_.find("-->", lt + 4);
        if (end == std::string::npos) failAt(lt, "unterminated comment");
        i = end + 3;
        continue;
      }
      if (text_.compare(lt, 2, "<?") == 0) {
        const std::size_t end = text_.find("?>", lt + 2);
        if (end == std::string::npos) failAt(lt, "unterminated processing instruction");
        i = end + 2;
        continue;
      }
      if (text_.compare(lt, 2, "<!") == 0) failAt(lt, "DOCTYPE and CDATA are not supported");
      if (text_.compare(lt, 2, "</") == 0) {
        std::size_t j = lt + 2;
        while (j < n && isNameChar(text_[j])) ++j;
        const std::string name = text_.substr(lt + 2, j - lt - 2);
        while (j < n && std::isspace(static_cast<unsigned char>(text_[j]))) ++j;
        if (j >= n || text_[j] != '>') failAt(lt, "malformed closing tag");
        if (open.empty() || elements_[static_cast<std::size_t>(open.back())].name != name) {
          failAt(lt, "closing tag </" + printable(name) + "> does not match the open element");
        }
        open.pop_back();
        i = j + 1;
        continue;
      }
      i = parseOpenTag(lt, open);
    }
    if (!open.empty()) {
      fail(elements_[static_cast<std::size_t>(open.back())], "is never closed");
    }
    if (elements_.empty() || elements_.front().name != "COLLADA") {
      throw FileError(path_, "the root element is not <COLLADA>");
    }
  }

  std::size_t parseOpenTag(std::size_t lt, std::vector<int>& open) {
    const std::size_t n = text_.size();
    std::size_t j = lt + 1;
    while (j < n && isNameChar(text_[j])) ++j;
    if (j == lt + 1) failAt(lt, "malformed tag");
    Element e;
    e.name = text_.substr(lt + 1, j - lt - 1);
    e.line = lineOf(lt);
    e.parent = open.empty() ? -1 : open.back();
    if (open.empty() && !elements_.empty()) failAt(lt, "a second root element");
    bool self_closing = false;
    for (;;) {
      while (j < n && std::isspace(static_cast<unsigned char>(text_[j]))) ++j;
      if (j >= n) failAt(lt, "unterminated tag <" + printable(e.name) + ">");
      if (text_[j] == '>') {
        ++j;
        break;
      }
      if (text_.compare(j, 2, "/>") == 0) {
        self_closing = true;
        j += 2;
        break;
      }
      const std::size_t key_start = j;
      while (j < n && isNameChar(text_[j])) ++j;
      if (j == key_start) failAt(j, "malformed attribute in <" + printable(e.name) + ">");
      std::string key = text_.substr(key_start, j - key_start);
      while (j < n && std::isspace(static_cast<unsigned char>(text_[j]))) ++j;
      if (j >= n || text_[j] != '=') failAt(j, "attribute " + printable(key) + " has no value");
      ++j;
      while (j < n && std::isspace(static_cast<unsigned char>(text_[j]))) ++j;
      if (j >= n || (text_[j] != '"' && text_[j] != '\'')) {
        failAt(j, "attribute " + printable(key) + " is not quoted");
      }
      const std::size_t close = text_.find(text_[j], j + 1);
      if (close == std::string::npos) failAt(j, "unterminated attribute " + printable(key));
      for (const auto& kv : e.attributes) {
        if (kv.first == key) failAt(j, "duplicate attribute " + printable(key));
      }
      e.attributes.emplace_back(std::move(key), text_.substr(j + 1, close - j - 1));
      j = close + 1;
    }
    const int index = static_cast<int>(elements_.size());
    if (e.parent >= 0) elements_[static_cast<std::size_t>(e.parent)].children.push_back(index);
    elements_.push_back(std::move(e));
    if (!self_closing) open.push_back(index);
    return j;
  }

  void indexIds() {
    for (std::size_t i = 0; i < elements_.size(); ++i) {
      const std::string* id = elements_[i].attribute("id");
      if (id == nullptr) continue;
      if (!ids_.emplace(*id, static_cast<int>(i)).second) {
        fail(elements_[i], "repeats the id \"" + printable(*id) + "\"");
      }
    }
  }

  // An unsigned integer attribute, or `fallback` when absent.
  std::uint64_t number(const Element& e, const char* key, std::uint64_t maximum,
                       std::int64_t fallback = -1) const {
    const std::string* value = e.attribute(key);
    if (value == nullptr) {
      if (fallback < 0) fail(e, std::string("has no ") + key + " attribute");
      return static_cast<std::uint64_t>(fallback);
    }
    std::uint64_t out = 0;
    if (!parseUnsigned(*value, maximum, &out)) {
      fail(e, std::string(key) + "=\"" + printable(*value) + "\" is not an integer in [0, " +
                  std::to_string(maximum) + "]");
    }
    return out;
  }

  static bool parseUnsigned(const std::string& s, std::uint64_t maximum, std::uint64_t* out) {
    std::size_t i = 0;
    while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
    std::size_t end = s.size();
    while (end > i && std::isspace(static_cast<unsigned char>(s[end - 1]))) --end;
    if (i == end) return false;
    std::uint64_t v = 0;
    for (; i < end; ++i) {
      if (!std::isdigit(static_cast<unsigned char>(s[i]))) return false;
      v = v * 10 + static_cast<std::uint64_t>(s[i] - '0');
      if (v > maximum) return false;
    }
    *out = v;
    return true;
  }

  static std::vector<std::string> tokens(const std::string& s) {
    std::vector<std::string> out;
    std::size_t i = 0;
    while (i < s.size()) {
      while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
      const std::size_t start = i;
      while (i < s.size() && !std::isspace(static_cast<unsigned char>(s[i]))) ++i;
      if (i > start) out.push_back(s.substr(start, i - start));
    }
    return out;
  }

  std::vector<std::uint64_t> indexList(const Element& e) const {
    std::vector<std::uint64_t> out;
    for (const std::string& t : tokens(e.text)) {
      std::uint64_t v = 0;
      if (!parseUnsigned(t, kMaxCount, &v)) {
        fail(e, "holds \"" + printable(t) + "\", not an index in [0, " + std::to_string(kMaxCount) +
                    "]");
      }
      out.push_back(v);
    }
    return out;
  }

  // The element a `#id` reference names, or -1.
  int resolve(const std::string& ref) const {
    if (ref.size() < 2 || ref[0] != '#') return -1;
    const auto it = ids_.find(ref.substr(1));
    return it == ids_.end() ? -1 : it->second;
  }

  int childNamed(int parent, const char* name) const {
    for (int c : elements_[static_cast<std::size_t>(parent)].children) {
      if (elements_[static_cast<std::size_t>(c)].name == name) return c;
    }
    return -1;
  }

  // The value count of an array element (checked against its content).
  std::uint64_t arrayCount(const Element& e) const {
    const std::uint64_t count = number(e, "count", kMaxCount);
    const std::vector<std::string> values = tokens(e.text);
    if (values.size() != count) {
      fail(e, "has count=\"" + std::to_string(count) + "\" but holds " +
                  std::to_string(values.size()) + " values");
    }
    if (e.name == "float_array" || e.name == "int_array") {
      // Plain decimal numbers only: assimp's own number parser reads no more than that.
      for (const std::string& v : values) {
        char* end = nullptr;
        std::strtod(v.c_str(), &end);
        if (end != v.c_str() + v.size() ||
            v.find_first_not_of("0123456789+-.eE") != std::string::npos) {
          fail(e, "holds \"" + printable(v) + "\", not a decimal number");
        }
      }
    }
    return count;
  }

  // The number of items a <source>'s accessor offers, requiring it to read floats when
  // `floats` (geometry data: assimp reads it as numbers whatever the array holds).
  std::uint64_t sourceItems(const Element& input, int source, bool floats) const {
    const Element& s = elements_[static_cast<std::size_t>(source)];
    if (s.name != "source") fail(input, "names <" + printable(s.name) + ">, not a <source>");
    const int technique = childNamed(source, "technique_common");
    const int accessor = technique < 0 ? -1 : childNamed(technique, "accessor");
    if (accessor < 0) fail(s, "has no <technique_common><accessor>");
    const Element& a = elements_[static_cast<std::size_t>(accessor)];
    const int array = resolve(a.attribute("source") ? *a.attribute("source") : "");
    if (array < 0) fail(a, "does not name an array of the file");
    if (floats && elements_[static_cast<std::size_t>(array)].name != "float_array") {
      fail(a, "reads geometry from a <" +
                  printable(elements_[static_cast<std::size_t>(array)].name) +
                  ">, not a <float_array>");
    }
    return number(a, "count", kMaxCount);
  }

  // The index bound of a primitive's input: the accessor's count, or for VERTEX the smallest
  // count among the <vertices> element's inputs.
  std::uint64_t inputItems(const Element& input) const {
    const std::string* semantic = input.attribute("semantic");
    const int target = resolve(input.attribute("source") ? *input.attribute("source") : "");
    if (target < 0) fail(input, "does not name an element of the file");
    if (*semantic != "VERTEX") return sourceItems(input, target, true);
    const Element& v = elements_[static_cast<std::size_t>(target)];
    if (v.name != "vertices") fail(input, "VERTEX names <" + printable(v.name) + ">");
    std::uint64_t items = kMaxCount;
    bool position = false;
    for (int c : v.children) {
      const Element& vi = elements_[static_cast<std::size_t>(c)];
      if (vi.name != "input") continue;
      position = position || *vi.attribute("semantic") == "POSITION";
      const int s = resolve(*vi.attribute("source"));
      items = std::min(items, sourceItems(vi, s, true));
    }
    if (!position) fail(v, "has no POSITION input");
    return items;
  }

  void checkElement(int index) {
    const Element& e = elements_[static_cast<std::size_t>(index)];
    if (isRefused(e.name)) fail(e, "is not supported in mesh files");
    if (e.name == "accessor") checkAccessor(e);
    if (e.name == "input") checkInput(e);
    for (const auto& [instance, kind] :
         {std::pair<const char*, const char*>{"instance_geometry", "geometry"},
          {"instance_node", "node"},
          {"instance_visual_scene", "visual_scene"}}) {
      if (e.name != instance) continue;
      const std::string* url = e.attribute("url");
      const int target = url == nullptr ? -1 : resolve(*url);
      if (target < 0) fail(e, "does not name an element of the file");
      if (elements_[static_cast<std::size_t>(target)].name != kind) {
        fail(e, std::string("does not name a <") + kind + ">");
      }
    }
  }

  void checkAccessor(const Element& e) {
    const std::uint64_t count = number(e, "count", kMaxCount);
    const std::uint64_t stride = number(e, "stride", kMaxCount, 1);
    const std::uint64_t offset = number(e, "offset", kMaxCount, 0);
    if (stride == 0) fail(e, "has stride 0");
    std::uint64_t params = 0;
    for (int c : e.children) params += elements_[static_cast<std::size_t>(c)].name == "param";
    if (params > stride) fail(e, "has more <param> than its stride");
    const int array = resolve(e.attribute("source") ? *e.attribute("source") : "");
    if (array < 0 || !isArray(elements_[static_cast<std::size_t>(array)].name)) {
      fail(e, "does not name an array of the file");
    }
    const std::uint64_t values = array_counts_.at(array);
    if (count > 0 && offset + count * stride > values) {
      fail(e, "reads " + std::to_string(offset + count * stride) + " values of an array of " +
                  std::to_string(values));
    }
  }

  void checkInput(const Element& e) {
    const std::string* semantic = e.attribute("semantic");
    if (semantic == nullptr || semantic->empty()) fail(e, "has no semantic");
    const std::string* source = e.attribute("source");
    if (source == nullptr || resolve(*source) < 0) {
      fail(e, "source does not name an element of the file");
    }
    number(e, "offset", kMaxInputOffset, 0);
    number(e, "set", kMaxInputSet, 0);
    if (e.parent >= 0 && elements_[static_cast<std::size_t>(e.parent)].name == "vertices") {
      sourceItems(e, resolve(*source), true);
    }
  }

  void checkPrimitive(const Element& e) {
    struct Input {
      std::uint64_t offset, items;
    };
    std::vector<Input> inputs;
    std::uint64_t stride = 0;
    bool vertex = false;
    std::vector<const Element*> lists;
    const Element* vcount = nullptr;
    for (int c : e.children) {
      const Element& child = elements_[static_cast<std::size_t>(c)];
      if (child.name == "input") {
        const std::uint64_t offset = number(child, "offset", kMaxInputOffset, 0);
        inputs.push_back({offset, inputItems(child)});
        stride = std::max(stride, offset + 1);
        vertex = vertex || *child.attribute("semantic") == "VERTEX";
      } else if (child.name == "p") {
        lists.push_back(&child);
      } else if (child.name == "vcount") {
        if (vcount != nullptr) fail(child, "is repeated");
        vcount = &child;
      }
    }
    if (!vertex) fail(e, "has no VERTEX input");
    const std::uint64_t count = number(e, "count", kMaxCount);
    std::uint64_t total = 0;
    for (const Element* p : lists) {
      const std::vector<std::uint64_t> indices = indexList(*p);
      if (indices.size() % stride != 0) {
        fail(*p, "holds " + std::to_string(indices.size()) +
                     " indices, not a multiple of the inputs' stride " + std::to_string(stride));
      }
      for (std::size_t k = 0; k < indices.size(); ++k) {
        for (const Input& in : inputs) {
          if (k % stride == in.offset && indices[k] >= in.items) {
            fail(*p, "index " + std::to_string(indices[k]) + " is out of range (" +
                         std::to_string(in.items) + " items)");
          }
        }
      }
      total += indices.size() / stride;
      if ((e.name == "polygons" || e.name == "linestrips") && indices.size() < stride) {
        fail(*p, "is empty");
      }
    }
    if (e.name == "polylist") {
      if (vcount == nullptr) fail(e, "has no <vcount>");
      const std::vector<std::uint64_t> sizes = indexList(*vcount);
      if (sizes.size() != count) fail(*vcount, "does not hold count=" + std::to_string(count));
      std::uint64_t sum = 0;
      for (std::uint64_t s : sizes) sum += s;
      if (lists.size() != 1 || sum != total) {
        fail(e, "has vertex counts summing to " + std::to_string(sum) + " for " +
                    std::to_string(total) + " indexed vertices");
      }
    } else if (vcount != nullptr) {
      fail(*vcount, "belongs only in a <polylist>");
    } else if (e.name == "triangles" || e.name == "lines") {
      const std::uint64_t corners = e.name == "triangles" ? 3 : 2;
      if (lists.size() > 1 || total != corners * count) {
        fail(e, "has count=\"" + std::to_string(count) + "\" but indexes " + std::to_string(total) +
                    " vertices");
      }
    } else if (lists.size() != count) {
      fail(e, "has count=\"" + std::to_string(count) + "\" but " + std::to_string(lists.size()) +
                  " <p>");
    }
  }

  // assimp expands <instance_node> recursively: a node that instances itself (directly or
  // through other nodes) never ends, and a long chain of instances overflows the stack.
  void checkInstanceNodes() const {
    std::unordered_map<int, std::vector<int>> edges;  // node -> nodes it instances
    for (const Element& e : elements_) {
      if (e.name != "instance_node") continue;
      const int target = resolve(*e.attribute("url"));  // a <node>: checkElement
      for (int a = e.parent; a >= 0; a = elements_[static_cast<std::size_t>(a)].parent) {
        if (elements_[static_cast<std::size_t>(a)].name == "node") edges[a].push_back(target);
      }
    }
    // Iterative depth-first search: the longest chain of instances below each node.
    std::unordered_map<int, std::size_t> depth;  // finished nodes
    std::unordered_set<int> on_path;
    for (const auto& root : edges) {
      if (depth.count(root.first) != 0) continue;
      std::vector<std::pair<int, std::size_t>> stack{{root.first, 0}};
      on_path.insert(root.first);
      while (!stack.empty()) {
        auto& [node, next] = stack.back();
        const std::vector<int>& out = edges[node];
        if (next < out.size()) {
          const int child = out[next++];
          if (on_path.count(child) != 0) {
            fail(elements_[static_cast<std::size_t>(child)],
                 "instances itself through <instance_node>");
          }
          if (depth.count(child) == 0) {
            on_path.insert(child);
            stack.emplace_back(child, 0);
          }
          continue;
        }
        std::size_t d = 0;
        for (int child : out) d = std::max(d, depth[child] + 1);
        if (d > kMaxInstanceChain) {
          fail(elements_[static_cast<std::size_t>(node)], "starts a chain of more than " +
                                                              std::to_string(kMaxInstanceChain) +
                                                              " <instance_node>");
        }
        depth[node] = d;
        on_path.erase(node);
        stack.pop_back();
      }
    }
  }

  const std::string& text_;
  const std::string& path_;
  std::vector<Element> elements_;
  std::unordered_map<std::string, int> ids_;
  std::unordered_map<int, std::uint64_t> array_counts_;
  std::size_t line_ = 1, line_pos_ = 0;
};

}  // namespace

void validateCollada(const std::string& text, const std::string& path) {
  Checker(text, path).run();
}

}  // namespace octomotion::detail
