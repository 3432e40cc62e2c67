#include "virtual_go/go/sgf.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>

#include "virtual_go/common/formatting.h"

namespace virtual_go {

namespace {

struct TextPosition {
  int line = 1;
  int column = 1;
};

struct PropertyValue {
  TextPosition at;   // of its '['
  std::string text;  // escapes resolved
};

struct Property {
  TextPosition at;  // of its first letter
  std::string id;   // the capitals of the identifier
  std::vector<PropertyValue> values;
};

// Walks the text byte by byte, keeping the line and the column (in characters: UTF-8
// continuation bytes do not count) of the next byte.
class Scanner {
 public:
  Scanner(const std::string& text, const std::string& source) : text_(text), source_(source) {
    if (text_.compare(0, 3, "\xEF\xBB\xBF") == 0) pos_ = 3;  // a UTF-8 byte order mark
  }

  bool at_end() const { return pos_ >= text_.size(); }
  char peek() const { return text_[pos_]; }
  TextPosition position() const { return here_; }

  char next() {
    const char c = text_[pos_++];
    const bool crlf = c == '\r' && !at_end() && peek() == '\n';
    if ((c == '\n' || c == '\r') && !crlf) {
      ++here_.line;
      here_.column = 1;
    } else if ((static_cast<unsigned char>(c) & 0xC0) != 0x80) {
      ++here_.column;
    }
    return c;
  }

  void skip_whitespace() {
    while (!at_end() && std::isspace(static_cast<unsigned char>(peek()))) next();
  }

  [[noreturn]] void fail(TextPosition at, const std::string& what) const {
    throw SgfError(source_, at.line, at.column, what);
  }

  // The next character as messages show it.
  std::string shown_next() const {
    if (at_end()) return "the end of the file";
    const unsigned char c = static_cast<unsigned char>(peek());
    if (std::isprint(c)) return std::string("'") + peek() + "'";
    return "byte " + std::to_string(static_cast<int>(c));
  }

 private:
  const std::string& text_;
  const std::string& source_;
  std::size_t pos_ = 0;
  TextPosition here_;
};

bool is_letter(char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'); }

// '[' ... ']' with SGF's escapes: a backslash takes the next character as it is, and a backslash
// before a line break removes both (a soft line break).
PropertyValue read_value(Scanner& in) {
  PropertyValue value;
  value.at = in.position();
  in.next();  // '['
  while (true) {
    if (in.at_end()) in.fail(value.at, "the value opened here is not closed with ']'");
    const char c = in.next();
    if (c == ']') return value;
    if (c == '\\') {
      if (in.at_end()) in.fail(value.at, "the value opened here is not closed with ']'");
      const char escaped = in.next();
      if (escaped == '\r' || escaped == '\n') {
        const char pair = escaped == '\r' ? '\n' : '\r';
        if (!in.at_end() && in.peek() == pair) in.next();
        continue;
      }
      value.text += escaped;
      continue;
    }
    value.text += c;
  }
}

// Properties up to the next ';', '(' or ')'. The scanner is after the node's ';'.
std::vector<Property> read_properties(Scanner& in) {
  std::vector<Property> properties;
  while (true) {
    in.skip_whitespace();
    if (in.at_end() || !is_letter(in.peek())) return properties;
    Property p;
    p.at = in.position();
    std::string written;
    while (!in.at_end() && is_letter(in.peek())) {
      const char c = in.next();
      written += c;
      if (c >= 'A' && c <= 'Z') p.id += c;  // FF[3]: lowercase letters are ignored
    }
    if (p.id.empty()) {
      in.fail(p.at, "property " + quote_user_text(written) +
                        " has no capital letter (SGF property names are capitals, e.g. B, AB)");
    }
    in.skip_whitespace();
    if (in.at_end() || in.peek() != '[') {
      in.fail(in.position(),
              "property " + p.id + " has no value: expected '[', found " + in.shown_next());
    }
    while (!in.at_end() && in.peek() == '[') {
      p.values.push_back(read_value(in));
      in.skip_whitespace();
    }
    properties.push_back(std::move(p));
  }
}

std::optional<int> small_integer(const std::string& text) {
  if (text.empty() || text.size() > 6) return std::nullopt;
  int n = 0;
  for (char c : text) {
    if (c < '0' || c > '9') return std::nullopt;
    n = 10 * n + (c - '0');
  }
  return n;
}

// SimpleText: line breaks become spaces.
std::string simple_text(std::string text) {
  std::replace_if(
      text.begin(), text.end(), [](char c) { return c == '\n' || c == '\r' || c == '\t'; }, ' ');
  return text;
}

class NodeReader {
 public:
  NodeReader(Scanner& in, SgfGame& game) : in_(in), game_(game) {}

  // Interprets one main-line node's properties.
  SgfNode read(TextPosition at, const std::vector<Property>& properties) {
    SgfNode node;
    node.line = at.line;
    std::set<std::string> seen;
    std::vector<std::pair<GoPoint, std::string>> set_here;  // setup points and their property
    for (const Property& p : properties) {
      if (!seen.insert(p.id).second) in_.fail(p.at, p.id + " appears twice in one node");
      if (p.id == "B" || p.id == "W") {
        if (node.move) in_.fail(p.at, "B and W in one node (a node holds one move)");
        node.move = read_move(p);
      } else if (p.id == "AB" || p.id == "AW" || p.id == "AE") {
        std::vector<GoPoint>& to = p.id == "AB"   ? node.add_black
                                   : p.id == "AW" ? node.add_white
                                                  : node.add_empty;
        for (const PropertyValue& v : p.values) {
          for (GoPoint q : point_list_entry(p, v)) {
            for (const auto& [earlier, by] : set_here) {
              if (earlier == q) {
                in_.fail(v.at, p.id + "[" + v.text + "]: point " + gtp_name(q) +
                                   " is set twice in one node (" + by + " and " + p.id + ")");
              }
            }
            set_here.emplace_back(q, p.id);
            to.push_back(q);
          }
        }
      } else if (p.id == "SZ") {
        const std::string& v = single(p).text;
        const std::size_t colon = v.find(':');
        const std::optional<int> x = small_integer(v.substr(0, colon));
        const std::optional<int> y =
            colon == std::string::npos ? x : small_integer(v.substr(colon + 1));
        if (!x || !y) in_.fail(p.values[0].at, "SZ[" + v + "]: not a board size");
        if (*x != kGoLines || *y != kGoLines) {
          in_.fail(p.values[0].at, "SZ[" + v + "]: a board of " + std::to_string(*x) + " x " +
                                       std::to_string(*y) + "; only 19 x 19 games are read");
        }
      } else if (p.id == "FF") {
        const std::optional<int> ff = small_integer(single(p).text);
        if (!ff || *ff < 1 || *ff > 4) {
          in_.fail(p.values[0].at,
                   "FF[" + p.values[0].text + "]: unknown file format (FF[1] to FF[4] are read)");
        }
        game_.file_format = *ff;
      } else if (p.id == "GM") {
        if (single(p).text != "1") {
          in_.fail(p.values[0].at, "GM[" + p.values[0].text + "]: not a game of Go (GM[1])");
        }
      } else if (p.id == "HA") {
        const std::optional<int> ha = small_integer(single(p).text);
        if (!ha || *ha > kGoLines * kGoLines) {
          in_.fail(p.values[0].at,
                   "HA[" + p.values[0].text + "]: not a number of handicap stones (0 to 361)");
        }
        game_.handicap = *ha;
      } else if (p.id == "PB") {
        game_.black_player = simple_text(single(p).text);
      } else if (p.id == "PW") {
        game_.white_player = simple_text(single(p).text);
      } else if (p.id == "RE") {
        game_.result = simple_text(single(p).text);
      }
      // Any other property: read, not needed for the position.
    }
    return node;
  }

 private:
  const PropertyValue& single(const Property& p) {
    if (p.values.size() != 1) {
      in_.fail(p.values[1].at, p.id + " takes one value, got " + std::to_string(p.values.size()));
    }
    return p.values[0];
  }

  SgfMove read_move(const Property& p) {
    const PropertyValue& v = single(p);
    SgfMove move;
    move.color = p.id == "B" ? StoneColor::black : StoneColor::white;
    if (v.text.empty() || v.text == "tt") return move;  // a pass ([tt] from FF[3], on 19 x 19)
    move.point = point(p, v, v.text);
    return move;
  }

  GoPoint point(const Property& p, const PropertyValue& v, const std::string& letters) {
    try {
      return parse_sgf_point(letters);
    } catch (const InvalidArgument&) {
      in_.fail(v.at, p.id + "[" + v.text + "]: " + quote_user_text(letters) +
                         " is not a point of a 19 x 19 board (two letters a-s, column then row "
                         "from the top left" +
                         (p.id == "B" || p.id == "W" ? std::string(", or [] or [tt] to pass)")
                                                     : std::string(")")));
    }
  }

  // One entry of a point list: a point, or FF[4]'s rectangle "aa:cc" between two corners.
  std::vector<GoPoint> point_list_entry(const Property& p, const PropertyValue& v) {
    const std::size_t colon = v.text.find(':');
    if (colon == std::string::npos) return {point(p, v, v.text)};
    const GoPoint a = point(p, v, v.text.substr(0, colon));
    const GoPoint b = point(p, v, v.text.substr(colon + 1));
    std::vector<GoPoint> points;
    for (int row = std::max(a.row, b.row); row >= std::min(a.row, b.row); --row) {
      for (int column = std::min(a.column, b.column); column <= std::max(a.column, b.column);
           ++column) {
        points.push_back({column, row});  // SGF's order: from the top left, row by row
      }
    }
    return points;
  }

  Scanner& in_;
  SgfGame& game_;
};

}  // namespace

int SgfGame::move_count() const {
  return static_cast<int>(std::count_if(main_line.begin(), main_line.end(),
                                        [](const SgfNode& n) { return n.move.has_value(); }));
}

SgfError::SgfError(const std::string& source, int line, int column, const std::string& what)
    : InvalidArgument("sgf", cut_user_text(source, 200) + ":" + std::to_string(line) + ":" +
                                 std::to_string(column) + ": " + what),
      line_(line),
      column_(column) {}

SgfGame parse_sgf(const std::string& text, const std::string& source) {
  // Collection = GameTree { GameTree }; GameTree = "(" Sequence { GameTree } ")";
  // Sequence = Node { Node }; Node = ";" { Property }. Walked with an explicit stack, so a deeply
  // nested file (some programs nest every move as a variation) cannot overflow the call stack.
  struct OpenTree {
    TextPosition at;
    bool main_line;
    int nodes = 0;
    int children = 0;
  };
  Scanner in(text, source);
  SgfGame game;
  NodeReader reader(in, game);
  std::vector<OpenTree> open;
  int games = 0;
  while (true) {
    in.skip_whitespace();
    if (in.at_end()) {
      if (!open.empty())
        in.fail(open.back().at, "the game tree opened here is not closed with ')'");
      if (games == 0) in.fail(in.position(), "no game: an SGF file starts with '(;'");
      return game;
    }
    const TextPosition at = in.position();
    const char c = in.peek();
    if (open.empty()) {
      if (c != '(') {
        in.fail(at, std::string(games == 0 ? "expected '(' to start a game"
                                           : "expected '(' (another game) or the end of the file") +
                        ", found " + in.shown_next());
      }
      in.next();
      open.push_back({at, games == 0});
      ++games;
      continue;
    }
    OpenTree& tree = open.back();
    if (c == '(') {
      if (tree.nodes == 0) in.fail(at, "a variation before the first node: expected ';'");
      const bool main_line = tree.main_line && tree.children == 0;
      ++tree.children;
      in.next();
      open.push_back({at, main_line});
    } else if (c == ')') {
      if (tree.nodes == 0) in.fail(at, "an empty game tree: '(' must be followed by a node ';'");
      in.next();
      open.pop_back();
    } else if (c == ';') {
      if (tree.children > 0) {
        in.fail(at, "a node after a variation (a tree's nodes come before its variations)");
      }
      in.next();
      const std::vector<Property> properties = read_properties(in);
      ++tree.nodes;
      if (tree.main_line) game.main_line.push_back(reader.read(at, properties));
    } else {
      in.fail(at, "expected ';' (a node), '(' (a variation) or ')', found " + in.shown_next());
    }
  }
}

SgfGame read_sgf_file(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) {
    throw InvalidArgument(
        "sgf", "sgf: cannot open " + quote_user_text(path, 200) + ": " + std::strerror(errno));
  }
  std::error_code error;
  const bool regular = std::filesystem::is_regular_file(path, error);
  const std::uintmax_t size = regular ? std::filesystem::file_size(path, error) : 0;
  if (!regular || error) {
    throw InvalidArgument("sgf", "sgf: cannot read " + quote_user_text(path, 200) +
                                     (error ? ": " + error.message() : ": not a regular file"));
  }
  if (size > kMaxSgfBytes) {
    throw InvalidArgument("sgf", "sgf: " + quote_user_text(path, 200) + " has " +
                                     std::to_string(size) + " bytes, more than the " +
                                     std::to_string(kMaxSgfBytes) + " this reader takes");
  }
  std::string text(static_cast<std::size_t>(size), '\0');
  if (!file.read(text.data(), static_cast<std::streamsize>(size))) {
    throw InvalidArgument("sgf", "sgf: cannot read " + quote_user_text(path, 200));
  }
  return parse_sgf(text, path);
}

}  // namespace virtual_go
