#pragma once
// Itasca 3DEC decks: the polyhedral blocks of a deck (3DEC 7 `block create polyhedron`, 3DEC 5 `poly`) read as
// ImportedBlocks, and blocks written as a deck that 3DEC runs with `program call`. 3DEC lists each face's corners
// clockwise seen from outside; the library's polyhedra have them counter-clockwise: both ways turn them around.

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <limits>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "blockdem/core/error.hpp"
#include "blockdem/core/types.hpp"
#include "blockdem/geometry/imported_block.hpp"
#include "blockdem/io/json.hpp"

namespace blockdem::io {

/// What a deck gave.
struct ThreeDecDeck {
  std::vector<geometry::ImportedBlock> blocks;  // "block 1", "block 2", ... in the deck's order
  std::size_t skipped_commands = 0;  // commands other than polyhedra (model new, block contact ...; a FISH function: one)
  /// Commands among the skipped ones that make, cut or delete blocks another way, call another file or start a new
  /// model ("deck.3ddat:12: block cut joint-set ..."): where there are any, 3DEC's blocks differ from those read.
  std::vector<std::string> not_followed;
};

namespace detail {

struct DeckToken {
  enum Kind { word, quoted, open, close, comma, unclosed_quote };
  Kind kind;
  std::string_view text;  // a word, or a quoted name without its quotes
  std::size_t line;
};

/// `word` is `keyword` or an abbreviation of it at least `shortest` characters long, in any case.
inline bool deck_keyword(const DeckToken& t, std::string_view keyword, std::size_t shortest) {
  if (t.kind != DeckToken::word || t.text.size() < shortest || t.text.size() > keyword.size()) return false;
  for (std::size_t i = 0; i < t.text.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(t.text[i])) != keyword[i]) return false;
  return true;
}

/// Adds the tokens of one line (a comment from ';' on dropped); true if the command goes on on the next line
/// (the line ends with '&' or '...').
inline bool deck_line_tokens(std::string_view line, std::size_t number, std::vector<DeckToken>& out) {
  const std::size_t first = out.size();
  const auto is_space = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; };
  for (std::size_t i = 0; i < line.size();) {
    const char c = line[i];
    if (c == ';') break;
    if (is_space(c)) {
      ++i;
    } else if (c == '(' || c == ')' || c == ',') {
      out.push_back({c == '(' ? DeckToken::open : c == ')' ? DeckToken::close : DeckToken::comma, line.substr(i, 1), number});
      ++i;
    } else if (c == '\'' || c == '"') {
      const auto end = line.find(c, i + 1);
      if (end == std::string_view::npos) {
        out.push_back({DeckToken::unclosed_quote, line.substr(i), number});
        return false;
      }
      out.push_back({DeckToken::quoted, line.substr(i + 1, end - i - 1), number});
      i = end + 1;
    } else {
      const std::size_t start = i;
      while (i < line.size() && !is_space(line[i]) && std::string_view(";(),'\"").find(line[i]) == std::string_view::npos) ++i;
      out.push_back({DeckToken::word, line.substr(start, i - start), number});
    }
  }
  if (out.size() == first || out.back().kind != DeckToken::word) return false;
  auto& last = out.back().text;
  const std::size_t cut = last.ends_with("...") ? 3 : last.ends_with('&') ? 1 : 0;
  if (cut == 0) return false;
  last.remove_suffix(cut);
  if (last.empty()) out.pop_back();
  return true;
}

/// A token as a message shows it (in quotes): at most 40 characters, control characters as '?'.
inline std::string deck_shown(const DeckToken& t, bool quotes = true) {
  std::string s(t.text.substr(0, 40));
  for (auto& c : s)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7F) c = '?';
  if (t.text.size() > 40) s += "...";
  return quotes ? "'" + s + "'" : s;
}

/// The blocks of one polyhedron command: its tokens from `i` on (after `block create polyhedron` or `poly`).
class DeckPolyhedron {
 public:
  DeckPolyhedron(const std::vector<DeckToken>& t, std::size_t i, const std::string& source) : t_(t), i_(i), source_(source) {}

  void read(ThreeDecDeck& deck, double weld) {
    std::vector<std::vector<Vec3>> faces;
    std::string group;
    bool grouped = false;
    while (i_ < t_.size()) {
      const DeckToken& k = t_[i_++];
      if (deck_keyword(k, "face", 4)) {
        std::vector<Vec3> corners;
        while (i_ < t_.size() && (t_[i_].kind == DeckToken::open || starts_number(t_[i_]))) corners.push_back(corner());
        if (corners.empty()) fail(k.line, "'face' with no corners after it (expected face (x,y,z) (x,y,z) (x,y,z) ...)");
        if (corners.size() < 3)
          fail(k.line, "a face with " + std::to_string(corners.size()) + " corners (a face needs at least 3: face (x,y,z) (x,y,z) (x,y,z) ...)");
        std::reverse(corners.begin(), corners.end());  // clockwise seen from outside -> counter-clockwise
        faces.push_back(std::move(corners));
      } else if (deck_keyword(k, "group", 2) || deck_keyword(k, "slot", 2)) {
        const bool is_group = deck_keyword(k, "group", 2);
        if (i_ >= t_.size() || (t_[i_].kind != DeckToken::word && t_[i_].kind != DeckToken::quoted)) {
          if (i_ < t_.size()) unexpected(t_[i_]);
          fail(k.line, std::string(is_group ? "'group'" : "'slot'") + " with no name after it (expected " + (is_group ? "group" : "slot") + " 'name')");
        }
        if (is_group && grouped) fail(k.line, "a second 'group' in one command (expected one group 'name')");
        if (is_group) group = std::string(t_[i_].text), grouped = true;
        ++i_;  // a slot's name: the library has no slots
      } else {
        unexpected(k);
      }
    }
    const std::size_t line = t_.front().line;
    if (faces.size() < 4)
      fail(line, "a polyhedron with " + std::to_string(faces.size()) +
                     " faces (a block needs at least 4: block create polyhedron face ... face ... face ... face ...)");
    Vec3 lo = faces.front().front(), hi = lo;
    for (const auto& f : faces)
      for (const auto& x : f) lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
    geometry::ImportedBlock block{"block " + std::to_string(deck.blocks.size() + 1), group, {}, {}, source_ + ":" + std::to_string(line)};
    const double tolerance = weld * std::clamp((hi - lo).norm(), 1.0, std::numeric_limits<double>::max());
    for (const auto& f : faces) geometry::add_face_by_corners(block, f, tolerance);
    deck.blocks.push_back(std::move(block));
  }

 private:
  [[noreturn]] void fail(std::size_t line, const std::string& what) const {
    throw InputError(source_ + ":" + std::to_string(line) + ": " + what);
  }
  [[noreturn]] void unexpected(const DeckToken& k) const {
    if (k.kind == DeckToken::unclosed_quote) fail(k.line, "a quote with no closing quote on its line (expected 'name' or \"name\")");
    fail(k.line, "unexpected " + (k.kind == DeckToken::quoted ? "name " : std::string()) + deck_shown(k) +
                     " in a polyhedron (expected face (x,y,z) (x,y,z) ..., group 'name' or the end of the command)");
  }
  static bool starts_number(const DeckToken& t) {
    return t.kind == DeckToken::word && (std::isdigit(static_cast<unsigned char>(t.text[0])) || t.text[0] == '-' || t.text[0] == '+' || t.text[0] == '.');
  }
  double number(const DeckToken& t) const {
    std::string_view s = t.text;
    if (s.size() > 1 && s[0] == '+' && s[1] != '-' && s[1] != '+') s.remove_prefix(1);
    double x = 0;
    const auto [end, error] = std::from_chars(s.data(), s.data() + s.size(), x);
    if (t.kind != DeckToken::word || error != std::errc() || end != s.data() + s.size() || !std::isfinite(x))
      fail(t.line, deck_shown(t) + " is not a number (expected a finite coordinate such as 1.5 or -2e-3)");
    return x;
  }
  // One corner: (x,y,z), (x y z) or x,y,z.
  Vec3 corner() {
    Vec3 x;
    const DeckToken& first = t_[i_];
    if (first.kind == DeckToken::open) {
      ++i_;
      for (int k = 0; k < 3; ++k) {
        if (k > 0 && i_ < t_.size() && t_[i_].kind == DeckToken::comma) ++i_;
        if (i_ >= t_.size()) fail(first.line, "a '(' with no ')' (expected a corner (x,y,z))");
        if (t_[i_].kind == DeckToken::close)
          fail(t_[i_].line, "a corner with " + std::to_string(k) + " coordinates (expected (x,y,z))");
        x[k] = number(t_[i_++]);
      }
      if (i_ >= t_.size()) fail(first.line, "a '(' with no ')' (expected a corner (x,y,z))");
      if (t_[i_].kind != DeckToken::close)
        fail(t_[i_].line, deck_shown(t_[i_]) + " after the third coordinate of a corner (expected ')': (x,y,z))");
      ++i_;
      return x;
    }
    x[0] = number(t_[i_++]);
    for (int k = 1; k < 3; ++k) {
      if (i_ >= t_.size() || t_[i_].kind != DeckToken::comma)
        fail(t_[i_ - 1].line, "a corner with " + std::to_string(k) + " coordinates (expected x,y,z or (x,y,z))");
      if (++i_ >= t_.size()) fail(t_[i_ - 1].line, "a ',' with no coordinate after it (expected x,y,z)");
      x[k] = number(t_[i_++]);
    }
    return x;
  }

  const std::vector<DeckToken>& t_;
  std::size_t i_;
  const std::string& source_;
};

/// "deck.3ddat:12: block cut joint-set dip 30": the start of a command, for ThreeDecDeck::not_followed.
inline std::string deck_command_text(const std::vector<DeckToken>& t, const std::string& source) {
  std::string s = source + ":" + std::to_string(t.front().line) + ":";
  for (std::size_t i = 0; i < t.size() && i < 8; ++i) (s += ' ') += deck_shown(t[i], t[i].kind == DeckToken::quoted);
  return s + (t.size() > 8 ? " ..." : "");
}

}  // namespace detail

/// The polyhedral blocks of a 3DEC deck's text; `source` names it in messages and in each block's origin
/// ("arch.3ddat:12", the command's first line). Read:
///   block create polyhedron face (x,y,z) (x,y,z) (x,y,z) ... face ... [group 'name' [slot 'name']]   (3DEC 7)
///   poly face x1,y1,z1 x2,y2,z2 x3,y3,z3 ... face ...                                                   (3DEC 5)
/// Keywords in any case and abbreviated (block: blo, create: cr, polyhedron: poly, group: gr, slot: sl; face in
/// full); a corner as (x,y,z), (x y z) or x,y,z; a group as 'name', "name" or name (a slot is ignored); comments
/// from ';'; a line ending in '&' or '...' goes on on the next. Each face's corners are clockwise seen from outside,
/// as 3DEC wants them: the blocks get them counter-clockwise. Corners within `weld` times the block's size (at least
/// 1 m) of an earlier corner are that corner. FISH functions (define ... end) are skipped; so is every other command,
/// counted. Throws InputError "source:line: what is wrong (what is expected)" for what cannot be read: a corner that
/// is not three finite numbers, an unclosed '(' or quote, a face with fewer than 3 corners, a polyhedron with fewer
/// than 4 faces, a FISH function without 'end'. Convexity, closure and planarity are geometry/polyhedron_check.hpp's.
inline ThreeDecDeck read_threedec_deck(std::string_view text, const std::string& source, double weld = 1e-9) {
  if (!(weld >= 0 && std::isfinite(weld))) throw InvalidArgument("3DEC deck: weld must be a finite fraction >= 0, got " + std::to_string(weld));
  using detail::deck_keyword;
  if (text.starts_with("\xEF\xBB\xBF")) text.remove_prefix(3);  // a UTF-8 byte order mark
  ThreeDecDeck deck;
  std::vector<detail::DeckToken> t;
  std::size_t line = 0, fish_from = 0;
  bool goes_on = false;
  for (std::size_t at = 0; at < text.size();) {
    const std::size_t end = std::min(text.find('\n', at), text.size()), before = t.size();
    // A blank or comment line within a continued command does not end it.
    goes_on = detail::deck_line_tokens(text.substr(at, end - at), ++line, t) || (goes_on && t.size() == before);
    at = end + 1;
    if ((goes_on && at < text.size()) || t.empty()) continue;
    const auto word = [&](std::size_t i, std::string_view keyword, std::size_t shortest) { return i < t.size() && deck_keyword(t[i], keyword, shortest); };
    const auto not_followed = [&] { deck.not_followed.push_back(detail::deck_command_text(t, source)); };
    if (fish_from > 0) {  // inside a FISH function: its lines are FISH, not commands
      if (t.size() == 1 && word(0, "end", 3)) fish_from = 0;
      t.clear();
      continue;
    }
    if ((word(0, "block", 3) && word(1, "create", 2) && word(2, "polyhedron", 4)) ||
        (word(0, "polyhedron", 4) && !(word(1, "brick", 2) || word(1, "prism", 2) || word(1, "tetrahedron", 2) || word(1, "drum", 2)))) {
      detail::DeckPolyhedron(t, word(0, "block", 3) ? 3 : 1, source).read(deck, weld);
      t.clear();
      continue;
    } else if (word(0, "define", 3) || (word(0, "fish", 2) && word(1, "define", 3))) {
      fish_from = line;
    } else if ((word(0, "block", 3) && (word(1, "create", 2) || word(1, "cut", 2) || word(1, "delete", 3))) || word(0, "polyhedron", 4) ||
               (word(0, "program", 3) && word(1, "call", 2)) || word(0, "call", 4) || word(0, "jset", 4) || word(0, "split", 3) ||
               word(0, "delete", 3) || word(0, "tunnel", 3) ||
               (!deck.blocks.empty() && ((word(0, "model", 3) && word(1, "new", 3)) || (t.size() == 1 && word(0, "new", 3))))) {
      not_followed();
    }
    ++deck.skipped_commands;
    t.clear();
  }
  if (fish_from > 0)
    throw InputError(source + ":" + std::to_string(fish_from) + ": a FISH function with no 'end' (expected a line 'end' closing it)");
  return deck;
}

/// Writes `blocks` as a 3DEC 7 deck: a comment header (`title`, units, how to run it), then per block a comment with
/// its name and one `block create polyhedron` command, a face per line (continued with ' &'), each face's corners
/// clockwise seen from outside as 3DEC wants them (the blocks' faces are counter-clockwise, as the library's
/// ConvexPolyhedron: they are written turned around), as (x,y,z) in the shortest text that reads back to the same
/// double; `group 'name'` if the block has a group. read_threedec_deck reads it back to the same vertices and faces
/// for blocks whose vertices come in the order their faces first use them and lie farther apart than the weld.
/// Throws InvalidArgument, before writing anything, for a block 3DEC could not take: fewer than 4 faces, a face with
/// fewer than 3 corners or one that is not a vertex, a corner that is not finite, a group with a quote, ';' or a
/// control character.
inline void write_threedec_deck(std::ostream& out, const std::vector<geometry::ImportedBlock>& blocks, std::string_view title) {
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    const auto& block = blocks[b];
    const auto fail = [&](const std::string& what) {
      throw InvalidArgument("3DEC deck: block " + std::to_string(b + 1) + " (\"" + block.name + "\"): " + what);
    };
    if (block.faces.size() < 4) fail(std::to_string(block.faces.size()) + " faces (a block needs at least 4)");
    for (const auto& face : block.faces) {
      if (face.size() < 3) fail("a face with " + std::to_string(face.size()) + " corners (a face needs at least 3)");
      for (int k : face)
        if (k < 0 || static_cast<std::size_t>(k) >= block.vertices.size()) fail("a face refers to corner " + std::to_string(k) + ", not in the block");
    }
    for (const auto& x : block.vertices)
      if (!x.allFinite()) fail("a corner is not a finite point");
    for (char c : block.group)
      if (c == '\'' || c == '"' || c == ';' || static_cast<unsigned char>(c) < 0x20 || c == 0x7F)
        fail("the group \"" + block.group + "\" holds a quote, ';' or a control character, which a deck cannot quote");
  }
  const auto comment = [&](std::string_view text) {  // one "; " line per line of text
    for (std::size_t at = 0; at <= text.size();) {
      const std::size_t end = std::min(text.find('\n', at), text.size());
      std::string line(text.substr(at, end - at));
      for (auto& c : line)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7F) c = ' ';
      out << "; " << line << "\n";
      at = end + 1;
    }
  };
  if (!title.empty()) comment(title);
  out << "; Units: SI (m). Written by blockdem: one 'block create polyhedron' per block, each face's corners clockwise\n"
         "; seen from outside the block. Run it in 3DEC: program call 'file.3ddat'\n";
  for (const auto& block : blocks) {
    out << "\n";
    if (!block.name.empty()) comment(block.name);
    out << "block create polyhedron &\n";
    for (std::size_t f = 0; f < block.faces.size(); ++f) {
      out << "  face";
      for (auto k = block.faces[f].rbegin(); k != block.faces[f].rend(); ++k) {
        const Vec3& x = block.vertices[static_cast<std::size_t>(*k)];
        out << " (" << JsonObject::number(x.x()) << ',' << JsonObject::number(x.y()) << ',' << JsonObject::number(x.z()) << ')';
      }
      out << (f + 1 < block.faces.size() || !block.group.empty() ? " &\n" : "\n");
    }
    if (!block.group.empty()) out << "  group '" << block.group << "'\n";
  }
}

}  // namespace blockdem::io
