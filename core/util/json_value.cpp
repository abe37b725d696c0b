#include "core/util/json_value.h"

#include <charconv>
#include <sstream>

#include <cmath>
#include "core/util/json_writer.h"
#include "core/util/utf8.h"

namespace handlab::util {
namespace {

class Parser {
 public:
  explicit Parser(std::string_view text) : s_(text) {}

  JsonValue document() {
    skip_space();
    JsonValue v = value(0);
    skip_space();
    if (at_ < s_.size()) fail("unexpected text after the JSON value");
    return v;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    std::size_t line = 1, column = 1;
    for (std::size_t i = 0; i < at_ && i < s_.size(); ++i) {
      if (s_[i] == '\n') {
        ++line;
        column = 1;
      } else {
        ++column;
      }
    }
    throw JsonError("JSON: " + what + " at line " + std::to_string(line) + ", column " +
                    std::to_string(column));
  }

  void skip_space() {
    while (at_ < s_.size() &&
           (s_[at_] == ' ' || s_[at_] == '\n' || s_[at_] == '\r' || s_[at_] == '\t'))
      ++at_;
  }

  bool consume(std::string_view word) {
    if (s_.substr(at_, word.size()) != word) return false;
    at_ += word.size();
    return true;
  }

  JsonValue value(int depth) {
    if (depth > 512) fail("nesting too deep");
    if (at_ >= s_.size()) fail("unexpected end of input");
    const char c = s_[at_];
    if (c == '{') return object(depth);
    if (c == '[') return array(depth);
    if (c == '"') return JsonValue(string());
    if (consume("true")) return JsonValue(true);
    if (consume("false")) return JsonValue(false);
    if (consume("null")) return JsonValue();
    if (c == '-' || (c >= '0' && c <= '9')) return JsonValue(number());
    fail(std::string("unexpected character '") + c + "'");
  }

  JsonValue object(int depth) {
    ++at_;
    JsonValue::Object members;
    skip_space();
    if (at_ < s_.size() && s_[at_] == '}') {
      ++at_;
      return JsonValue(std::move(members));
    }
    while (true) {
      skip_space();
      if (at_ >= s_.size() || s_[at_] != '"') fail("expected a member name");
      std::string key = string();
      skip_space();
      if (at_ >= s_.size() || s_[at_] != ':') fail("expected ':'");
      ++at_;
      skip_space();
      members.emplace_back(std::move(key), value(depth + 1));
      skip_space();
      if (at_ < s_.size() && s_[at_] == ',') {
        ++at_;
        continue;
      }
      if (at_ < s_.size() && s_[at_] == '}') {
        ++at_;
        return JsonValue(std::move(members));
      }
      fail("expected ',' or '}'");
    }
  }

  JsonValue array(int depth) {
    ++at_;
    JsonValue::Array items;
    skip_space();
    if (at_ < s_.size() && s_[at_] == ']') {
      ++at_;
      return JsonValue(std::move(items));
    }
    while (true) {
      skip_space();
      items.push_back(value(depth + 1));
      skip_space();
      if (at_ < s_.size() && s_[at_] == ',') {
        ++at_;
        continue;
      }
      if (at_ < s_.size() && s_[at_] == ']') {
        ++at_;
        return JsonValue(std::move(items));
      }
      fail("expected ',' or ']'");
    }
  }

  double number() {
    const std::size_t start = at_;
    if (s_[at_] == '-') ++at_;
    auto digits = [&] {
      const std::size_t from = at_;
      while (at_ < s_.size() && s_[at_] >= '0' && s_[at_] <= '9') ++at_;
      return at_ > from;
    };
    if (!digits()) fail("malformed number");
    if (at_ < s_.size() && s_[at_] == '.') {
      ++at_;
      if (!digits()) fail("malformed number");
    }
    if (at_ < s_.size() && (s_[at_] == 'e' || s_[at_] == 'E')) {
      ++at_;
      if (at_ < s_.size() && (s_[at_] == '+' || s_[at_] == '-')) ++at_;
      if (!digits()) fail("malformed number");
    }
    double v = 0.0;
    const auto result = std::from_chars(s_.data() + start, s_.data() + at_, v);
    if (result.ec == std::errc::result_out_of_range) return s_[start] == '-' ? -HUGE_VAL : HUGE_VAL;
    return v;
  }

  unsigned hex4() {
    if (at_ + 4 > s_.size()) fail("truncated \\u escape");
    unsigned code = 0;
    for (int i = 0; i < 4; ++i) {
      const char h = s_[at_++];
      code <<= 4;
      if (h >= '0' && h <= '9')
        code |= unsigned(h - '0');
      else if (h >= 'a' && h <= 'f')
        code |= unsigned(h - 'a' + 10);
      else if (h >= 'A' && h <= 'F')
        code |= unsigned(h - 'A' + 10);
      else
        fail("bad \\u escape");
    }
    return code;
  }

  std::string string() {
    ++at_;  // opening quote
    std::string out;
    while (true) {
      if (at_ >= s_.size()) fail("unterminated string");
      const char c = s_[at_++];
      if (c == '"') return out;
      if (static_cast<unsigned char>(c) < 0x20) fail("control character in a string");
      if (c != '\\') {
        out += c;
        continue;
      }
      if (at_ >= s_.size()) fail("unterminated escape");
      switch (s_[at_++]) {
        case '"':
          out += '"';
          break;
        case '\\':
          out += '\\';
          break;
        case '/':
          out += '/';
          break;
        case 'b':
          out += '\b';
          break;
        case 'f':
          out += '\f';
          break;
        case 'n':
          out += '\n';
          break;
        case 'r':
          out += '\r';
          break;
        case 't':
          out += '\t';
          break;
        case 'u': {
          unsigned code = hex4();
          if (code >= 0xD800 && code < 0xDC00 && s_.substr(at_, 2) == "\\u") {
            at_ += 2;
            const unsigned low = hex4();
            if (low >= 0xDC00 && low < 0xE000)
              code = 0x10000 + ((code - 0xD800) << 10) + (low - 0xDC00);
            else
              fail("bad surrogate pair");
          }
          append_utf8(out, code);
          break;
        }
        default:
          fail("unknown escape");
      }
    }
  }

  std::string_view s_;
  std::size_t at_ = 0;
};

}  // namespace

JsonValue JsonValue::parse(std::string_view text) {
  return Parser(text).document();
}

bool JsonValue::as_bool() const {
  if (!is_bool()) throw JsonError("JSON: expected true or false");
  return std::get<bool>(v_);
}
double JsonValue::as_number() const {
  if (!is_number()) throw JsonError("JSON: expected a number");
  return std::get<double>(v_);
}
const std::string& JsonValue::as_string() const {
  if (!is_string()) throw JsonError("JSON: expected a string");
  return std::get<std::string>(v_);
}
const JsonValue::Array& JsonValue::as_array() const {
  if (!is_array()) throw JsonError("JSON: expected an array");
  return std::get<Array>(v_);
}
const JsonValue::Object& JsonValue::as_object() const {
  if (!is_object()) throw JsonError("JSON: expected an object");
  return std::get<Object>(v_);
}

const JsonValue* JsonValue::find(std::string_view key) const {
  if (!is_object()) return nullptr;
  for (const auto& [name, value] : std::get<Object>(v_))
    if (name == key) return &value;
  return nullptr;
}

const JsonValue& JsonValue::operator[](std::string_view key) const {
  const JsonValue* v = find(key);
  if (!v) throw JsonError("JSON: no member '" + std::string(key) + "'");
  return *v;
}

std::string JsonValue::dump() const {
  std::ostringstream out;
  JsonWriter writer(out, 0);
  struct Visitor {
    JsonWriter& w;
    void operator()(const JsonValue& v) const {
      if (v.is_null())
        w.null();
      else if (v.is_bool())
        w.value(v.as_bool());
      else if (v.is_number())
        w.value(v.as_number());
      else if (v.is_string())
        w.value(std::string_view(v.as_string()));
      else if (v.is_array()) {
        w.begin_array();
        for (const auto& item : v.as_array()) (*this)(item);
        w.end_array();
      } else {
        w.begin_object();
        for (const auto& [key, item] : v.as_object()) {
          w.key(key);
          (*this)(item);
        }
        w.end_object();
      }
    }
  };
  Visitor{writer}(*this);
  std::string text = out.str();
  while (!text.empty() && text.back() == '\n') text.pop_back();
  return text;
}

std::size_t JsonValue::size() const {
  if (is_array()) return std::get<Array>(v_).size();
  if (is_object()) return std::get<Object>(v_).size();
  return 0;
}

}  // namespace handlab::util
