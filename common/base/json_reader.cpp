#include "common/base/json_reader.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>
#include <vector>

#include "common/base/error.h"

namespace glint {
namespace {

std::string typeName(const nlohmann::json& v) {
  if (v.is_null()) return "null";
  if (v.is_boolean()) return "a boolean";
  if (v.is_number()) return "a number";
  if (v.is_string()) return "a string";
  if (v.is_array()) return "an array";
  return "an object";
}

std::string format(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

// Follows the parser through the document so that an error the parser finds
// in a value can name the value's path, as JsonReader would.
class PathTracker {
 public:
  bool event(nlohmann::json::parse_event_t event, const nlohmann::json& parsed) {
    using Event = nlohmann::json::parse_event_t;
    switch (event) {
      case Event::object_start:
      case Event::array_start:
        levels_.push_back({event == Event::array_start, "", 0});
        break;
      case Event::key:
        levels_.back().key = parsed.get<std::string>();
        if (!levels_.back().keys.insert(levels_.back().key).second && duplicate_.empty()) {
          duplicate_ = levels_.back().key;
          duplicatePath_ = parentPath();
        }
        break;
      case Event::object_end:
      case Event::array_end:
        levels_.pop_back();
        nextElement();
        break;
      case Event::value:
        nextElement();
        break;
    }
    return true;
  }

  // The path of the value being parsed: "objects[0].radius".
  std::string path() const { return pathOf(levels_.size()); }
  // The first key written twice in one object, and that object's path; ""
  // when none was.
  const std::string& duplicate() const { return duplicate_; }
  const std::string& duplicatePath() const { return duplicatePath_; }

 private:
  struct Level {
    bool array;
    std::string key;    // objects: the key being read
    std::size_t index;  // arrays: the element being read
    std::set<std::string> keys{};  // objects: the keys read so far
  };
  std::string pathOf(std::size_t levels) const {
    std::string out;
    for (std::size_t i = 0; i < levels; ++i) {
      const Level& l = levels_[i];
      out += l.array ? "[" + std::to_string(l.index) + "]" : (out.empty() ? "" : ".") + l.key;
    }
    return out.empty() ? "(top level)" : out;
  }
  std::string parentPath() const { return pathOf(levels_.size() - 1); }
  void nextElement() {
    if (!levels_.empty() && levels_.back().array) ++levels_.back().index;
  }
  std::vector<Level> levels_;
  std::string duplicate_;
  std::string duplicatePath_;
};

// Scene files may carry // and /* */ comments (docs/scene-format.md).
constexpr bool kIgnoreComments = true;

// Where a value the parser refused lies: the text parsed again with a
// PathTracker (only on that error, so that good scenes parse at full speed).
std::string pathOfBadValue(std::string_view text) {
  PathTracker tracker;
  try {
    const nlohmann::json unused =
        nlohmann::json::parse(
            text,
            [&tracker](int, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
              return tracker.event(event, parsed);
            },
            true, kIgnoreComments);
  } catch (const nlohmann::json::exception&) {
    return tracker.path();
  }
  return "(top level)";
}

// The members of every object in a parsed document (a key written twice in
// one object is kept once).
std::size_t memberCount(const nlohmann::json& doc) {
  std::size_t members = 0;
  std::vector<const nlohmann::json*> open{&doc};
  while (!open.empty()) {
    const nlohmann::json* v = open.back();
    open.pop_back();
    if (v->is_object()) members += v->size();
    if (!v->is_structured()) continue;
    for (const nlohmann::json& child : *v) open.push_back(&child);
  }
  return members;
}

// The first key the text writes twice in one object, as an error naming the
// object (the text parsed again with a PathTracker, only then).
std::string duplicateKeyError(std::string_view text) {
  PathTracker tracker;
  const nlohmann::json unused = nlohmann::json::parse(
      text,
      [&tracker](int, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
        return tracker.event(event, parsed);
      },
      true, kIgnoreComments);
  return tracker.duplicatePath() + ": the key '" + tracker.duplicate() +
         "' is written twice (a later one would silently replace the first)";
}

// The index just past the string that opens at text[i] (a '"').
std::size_t skipString(std::string_view text, std::size_t i) {
  for (++i; i < text.size(); ++i) {
    if (text[i] == '\\') ++i;
    else if (text[i] == '"') return i + 1;
  }
  return text.size();
}

// The index just past the comment that opens at text[i] ('/'), or i + 1.
std::size_t skipComment(std::string_view text, std::size_t i) {
  if (text.substr(i, 2) == "//") {
    const std::size_t end = text.find('\n', i);
    return end == std::string_view::npos ? text.size() : end + 1;
  }
  if (text.substr(i, 2) == "/*") {
    const std::size_t end = text.find("*/", i + 2);
    return end == std::string_view::npos ? text.size() : end + 2;
  }
  return i + 1;
}

}  // namespace

JsonShape measureJson(std::string_view text) {
  JsonShape shape;
  shape.values = 1;
  int depth = 0;
  for (std::size_t i = 0; i < text.size();) {
    switch (text[i]) {
      case '"':
        i = skipString(text, i);
        continue;
      case '/':
        i = skipComment(text, i);
        continue;
      case '[':
      case '{':
        shape.depth = std::max(shape.depth, ++depth);
        ++shape.values;
        break;
      case ']':
      case '}':
        --depth;
        break;
      case ',':
        ++shape.values;
        break;
      case ':':
        ++shape.members;
        break;
      default:
        break;
    }
    ++i;
  }
  return shape;
}

nlohmann::json parseJson(std::string_view text, const JsonShape& shape) {
  try {
    nlohmann::json doc = nlohmann::json::parse(text, nullptr, true, kIgnoreComments);
    if (memberCount(doc) != shape.members) throw InputError(duplicateKeyError(text));
    return doc;
  } catch (const nlohmann::json::parse_error& e) {
    // e.what() reads "[json.exception.parse_error.101] parse error at line 3, column 5: ..."
    const std::string what = e.what();
    const auto at = what.find("parse error");
    throw InputError("not valid JSON: " + (at == std::string::npos ? what : what.substr(at)));
  } catch (const nlohmann::json::exception& e) {
    // "[json.exception.out_of_range.406] number overflow parsing '1e999'"
    const std::string what = e.what();
    const auto at = what.find("] ");
    throw InputError(pathOfBadValue(text) + ": " + (at == std::string::npos ? what : what.substr(at + 2)) +
                     " (out of range)");
  }
}

JsonReader::JsonReader(const nlohmann::json& value, std::string path)
    : value_(value), path_(std::move(path)) {}

void JsonReader::fail(const std::string& what) const {
  throw InputError((path_.empty() ? std::string("(top level)") : path_) + ": " + what);
}

void JsonReader::requireObject() const {
  if (!value_.is_object()) fail("must be an object, not " + typeName(value_));
}

void JsonReader::allowKeys(std::initializer_list<const char*> keys) const {
  requireObject();
  for (const auto& [key, ignored] : value_.items()) {
    bool known = false;
    for (const char* k : keys) known = known || key == k;
    if (!known) {
      std::string list;
      for (const char* k : keys) list += std::string(list.empty() ? "" : ", ") + k;
      JsonReader(value_, path_.empty() ? key : path_ + "." + key)
          .fail("unknown key (allowed here: " + list + ")");
    }
  }
}

bool JsonReader::has(const char* key) const { return value_.is_object() && value_.contains(key); }

JsonReader JsonReader::operator[](const char* key) const {
  requireObject();
  const std::string child = path_.empty() ? key : path_ + "." + key;
  const auto it = value_.find(key);
  if (it == value_.end()) JsonReader(value_, child).fail("required key is missing");
  return JsonReader(*it, child);
}

std::optional<JsonReader> JsonReader::find(const char* key) const {
  if (!has(key)) return std::nullopt;
  return (*this)[key];
}

std::size_t JsonReader::arraySize() const {
  if (!value_.is_array()) fail("must be an array, not " + typeName(value_));
  return value_.size();
}

JsonReader JsonReader::at(std::size_t i) const {
  arraySize();
  return JsonReader(value_[i], path_ + "[" + std::to_string(i) + "]");
}

float JsonReader::number(float lo, float hi, bool loExclusive) const {
  if (!value_.is_number()) fail("must be a number, not " + typeName(value_));
  const double d = value_.get<double>();
  const auto f = static_cast<float>(d);
  if (!std::isfinite(d) || !std::isfinite(f)) fail("must be a finite number");
  if ((loExclusive ? f > lo : f >= lo) && f <= hi) return f;
  // The whole range, said once, whichever side the value fell.
  const bool floor = lo > -std::numeric_limits<float>::max();
  const bool ceiling = hi < std::numeric_limits<float>::max();
  if (floor && ceiling) {
    fail("must be in " + std::string(loExclusive ? "(" : "[") + format(lo) + ", " + format(hi) + "]");
  }
  if (ceiling) fail("must be <= " + format(hi));
  fail(loExclusive ? "must be > " + format(lo) : "must be >= " + format(lo));
}

int JsonReader::integer(long long lo, long long hi) const {
  if (!value_.is_number_integer()) {
    fail(value_.is_number() ? "must be a whole number" : "must be a whole number, not " + typeName(value_));
  }
  // Unsigned values above the signed range read as negative, so check both.
  if (value_.is_number_unsigned() && value_.get<unsigned long long>() > static_cast<unsigned long long>(hi)) {
    fail("must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  }
  const long long v = value_.get<long long>();
  if (v < lo || v > hi) fail("must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  return static_cast<int>(v);
}

std::uint32_t JsonReader::index(std::size_t count) const {
  if (!value_.is_number_integer()) fail("must be a whole number, not " + typeName(value_));
  if (value_.is_number_unsigned() ? value_.get<unsigned long long>() >= count
                                  : (value_.get<long long>() < 0 ||
                                     static_cast<unsigned long long>(value_.get<long long>()) >= count)) {
    fail("index out of range: must be in [0, " + std::to_string(count) + ")");
  }
  return static_cast<std::uint32_t>(value_.get<unsigned long long>());
}

std::string JsonReader::string() const {
  if (!value_.is_string()) fail("must be a string, not " + typeName(value_));
  return value_.get<std::string>();
}

bool JsonReader::boolean() const {
  if (!value_.is_boolean()) fail("must be true or false, not " + typeName(value_));
  return value_.get<bool>();
}

glm::vec3 JsonReader::vec3() const {
  if (!value_.is_array() || value_.size() != 3) fail("must be an array of 3 numbers");
  return {at(0).number(), at(1).number(), at(2).number()};
}

glm::vec2 JsonReader::vec2() const {
  if (!value_.is_array() || value_.size() != 2) fail("must be an array of 2 numbers");
  return {at(0).number(), at(1).number()};
}

float JsonReader::number(const char* key, float fallback, float lo, float hi, bool loExclusive) const {
  const std::optional<JsonReader> v = find(key);
  return v ? v->number(lo, hi, loExclusive) : fallback;
}

glm::vec3 JsonReader::vec3(const char* key, const glm::vec3& fallback) const {
  const std::optional<JsonReader> v = find(key);
  return v ? v->vec3() : fallback;
}

}  // namespace glint
