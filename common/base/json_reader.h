#pragma once

#include <cstddef>
#include <initializer_list>
#include <limits>
#include <optional>
#include <string>
#include <string_view>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

namespace glint {

// The shape of JSON text, found by one pass over its bytes before it is
// parsed (strings and comments skipped): how deep its arrays and objects
// nest, and about how many values and object members it holds, which decide
// the memory its parse takes. Malformed text gives some answer; the parse
// then refuses it.
struct JsonShape {
  std::size_t values = 0;   // containers and scalars (separators + containers + 1: a bound from above)
  std::size_t members = 0;  // an object's key-value pairs
  int depth = 0;            // deepest nesting of arrays and objects
};
JsonShape measureJson(std::string_view text);

// Parses JSON text. Errors are InputErrors: a syntax error gives its line
// and column, a number out of range (1e999) the path of the value
// ("objects[0].radius: number out of range"), a key written twice in one
// object the object's path and the key. `shape` is measureJson(text), which
// the caller has measured for its limits.
nlohmann::json parseJson(std::string_view text, const JsonShape& shape);

// Read access to a parsed JSON value that knows its own path in the document
// ("objects[3].radius"), so that every error names the place. Each getter
// checks the type and range and throws InputError("path: what is wrong").
class JsonReader {
 public:
  JsonReader(const nlohmann::json& value, std::string path);

  const std::string& path() const { return path_; }
  const nlohmann::json& raw() const { return value_; }
  [[noreturn]] void fail(const std::string& what) const;

  // Objects. allowKeys fails on a key outside the list (typos must not be
  // silently ignored).
  void requireObject() const;
  void allowKeys(std::initializer_list<const char*> keys) const;
  bool has(const char* key) const;
  JsonReader operator[](const char* key) const;  // required key
  std::optional<JsonReader> find(const char* key) const;

  // Arrays.
  std::size_t arraySize() const;
  JsonReader at(std::size_t i) const;

  // Scalars. number() is a finite float in [lo, hi] (or (lo, hi] when
  // loExclusive).
  float number(float lo = -std::numeric_limits<float>::max(),
               float hi = std::numeric_limits<float>::max(), bool loExclusive = false) const;
  int integer(long long lo, long long hi) const;
  std::uint32_t index(std::size_t count) const;  // an integer in [0, count)
  std::string string() const;
  bool boolean() const;
  glm::vec3 vec3() const;
  glm::vec2 vec2() const;
  bool isNumber() const { return value_.is_number(); }
  bool isString() const { return value_.is_string(); }
  bool isBoolean() const { return value_.is_boolean(); }
  bool isArray() const { return value_.is_array(); }

  // Optional keys with the scene format's defaults.
  float number(const char* key, float fallback, float lo = -std::numeric_limits<float>::max(),
               float hi = std::numeric_limits<float>::max(), bool loExclusive = false) const;
  glm::vec3 vec3(const char* key, const glm::vec3& fallback) const;

 private:
  const nlohmann::json& value_;
  std::string path_;
};

}  // namespace glint
