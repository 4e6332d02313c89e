#include "brep/step_shared_geometry.hpp"

#include <algorithm>
#include <charconv>
#include <cstring>
#include <stdexcept>
#include <string_view>
#include <unordered_map>
#include <unordered_set>
#include <vector>

namespace steady {

namespace {

using Keywords = std::unordered_set<std::string_view>;

// Geometric values: two equal ones are one value wherever they are written. Surfaces are not among them (a face
// keeps its own), nor anything with an identity of its own (topology, products, representations, styles).
const Keywords& value_keywords() {
  static const Keywords k = {
      "CARTESIAN_POINT", "DIRECTION", "VECTOR", "AXIS1_PLACEMENT", "AXIS2_PLACEMENT_2D", "AXIS2_PLACEMENT_3D", "LINE",
      "CIRCLE", "ELLIPSE", "HYPERBOLA", "PARABOLA", "B_SPLINE_CURVE_WITH_KNOTS", "BEZIER_CURVE", "TRIMMED_CURVE",
      "PCURVE", "DEFINITIONAL_REPRESENTATION", "SURFACE_CURVE", "SEAM_CURVE",
      // records of the complex entities that are values: rational B-spline curves, 2D parameter contexts
      "BOUNDED_CURVE", "B_SPLINE_CURVE", "RATIONAL_B_SPLINE_CURVE", "CURVE", "GEOMETRIC_REPRESENTATION_ITEM",
      "REPRESENTATION_ITEM", "GEOMETRIC_REPRESENTATION_CONTEXT", "PARAMETRIC_REPRESENTATION_CONTEXT",
      "REPRESENTATION_CONTEXT"};
  return k;
}

// What may refer to a shared value besides other values: topology and surfaces. A value that anything else refers
// to (an assembly's placements, listed in a shape representation's set of items) keeps its own entity.
const Keywords& geometry_keywords() {
  static const Keywords k = {
      "VERTEX_POINT", "EDGE_CURVE", "ORIENTED_EDGE", "EDGE_LOOP", "VERTEX_LOOP", "FACE_BOUND", "FACE_OUTER_BOUND",
      "ADVANCED_FACE", "FACE_SURFACE", "PLANE", "CYLINDRICAL_SURFACE", "CONICAL_SURFACE", "SPHERICAL_SURFACE",
      "TOROIDAL_SURFACE", "DEGENERATE_TOROIDAL_SURFACE", "B_SPLINE_SURFACE_WITH_KNOTS", "SURFACE_OF_LINEAR_EXTRUSION",
      "SURFACE_OF_REVOLUTION", "OFFSET_SURFACE", "RECTANGULAR_TRIMMED_SURFACE", "BOUNDED_SURFACE", "B_SPLINE_SURFACE",
      "RATIONAL_B_SPLINE_SURFACE", "SURFACE"};
  return k;
}

bool is_word_char(char c) {
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '-';
}
bool is_letter(char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || c == '_' || c == '!'; }
bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }
// Characters copied as they are inside a record: neither a string's quote, a space, a comment's '/', the record's
// end, a reference's '#' nor a comma (where lines are wrapped).
bool is_plain(char c) { return c != '\'' && !is_space(c) && c != '/' && c != ';' && c != '#' && c != ','; }

[[noreturn]] void malformed(const std::string& what) {
  throw std::runtime_error("STEP sharing: " + what + " (not a file as OpenCASCADE's writer gives it)");
}

// The entity number whose digits start at text[at] (after its '#'); `at` moves past them.
long entity_number(const std::string& text, std::size_t& at) {
  const std::size_t start = at;
  long id = 0;
  while (at < text.size() && text[at] >= '0' && text[at] <= '9' && at - start < 15) id = id * 10 + (text[at++] - '0');
  if (at == start || (at < text.size() && text[at] >= '0' && text[at] <= '9'))
    malformed("an entity number of no digits or more than 15");
  return id;
}

struct Record {
  long id = 0;
  std::size_t begin = 0, size = 0;       // the record's compacted text in Records::text
  std::size_t refs_begin = 0, refs = 0;  // the entities it refers to, in order, in Records::refs
  bool may_share = false;                // a geometric value that only geometry and topology refer to
  long canonical = -1;                   // the id of the equal value written for it (its own id when kept)
  bool visiting = false;
};

struct Records {
  std::string text;        // every record's compacted text, one after another
  std::vector<long> refs;  // every record's references, one after another
  std::vector<Record> list;
  std::vector<int> index_of_id;  // record index of an entity id, -1 where none
  std::string_view body(const Record& r) const { return std::string_view(text).substr(r.begin, r.size); }
  long ref(const Record& r, std::size_t k) const { return refs[r.refs_begin + k]; }
  int index(long id) const {
    if (id < 0 || id >= static_cast<long>(index_of_id.size()) || index_of_id[id] < 0)
      malformed("a reference to #" + std::to_string(id) + ", which the file does not define");
    return index_of_id[id];
  }
};

// The keywords of a record: its type, or the types of a complex entity's records.
std::vector<std::string_view> keywords_of(std::string_view body) {
  std::vector<std::string_view> out;
  if (body.empty()) return out;
  if (body[0] != '(') {
    out.push_back(body.substr(0, body.find('(')));
    return out;
  }
  int depth = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < body.size(); ++i) {
    const char c = body[i];
    if (in_string) {
      if (c == '\'') in_string = false;  // '' inside a string reads as two quotes: leave and enter again
    } else if (c == '\'') {
      in_string = true;
    } else if (c == '(') {
      ++depth;
    } else if (c == ')') {
      --depth;
    } else if (depth == 1 && is_letter(c) && (i == 0 || !is_word_char(body[i - 1]))) {
      std::size_t j = i;
      while (j < body.size() && is_word_char(body[j])) ++j;
      out.push_back(body.substr(i, j - i));
      i = j - 1;
    }
  }
  return out;
}

bool all_in(const std::vector<std::string_view>& words, const Keywords& a, const Keywords* b = nullptr) {
  if (words.empty()) return false;
  for (std::string_view w : words)
    if (!a.count(w) && !(b && b->count(w))) return false;
  return true;
}

// Compacts one record's parameters, from text[at] up to its ';', to text[write] on: whitespace outside strings
// dropped (one space kept where a keyword follows a word or a closing parenthesis: the records of a complex entity),
// comments too. What is written never passes what is read (only spaces are dropped, and a space is kept only where
// one was), so the text is compacted in place. Collects the record's references; returns the position after ';'.
std::size_t read_record_body(Records& records, std::size_t at, std::size_t& write, Record& r) {
  std::string& text = records.text;
  char* const buf = text.data();
  const auto emit = [&](std::size_t from, std::size_t n) {
    std::memmove(buf + write, buf + from, n);
    write += n;
  };
  r.begin = write;
  r.refs_begin = records.refs.size();
  bool space = false;
  while (true) {
    if (at >= text.size()) malformed("a record without its ';'");
    const char c = text[at];
    if (c == '\'') {  // a string, copied as it is ('' is a quote inside it)
      const std::size_t end = text.find('\'', at + 1);
      if (end == std::string::npos) malformed("a string without its end");
      emit(at, end + 1 - at);
      at = end + 1;
      space = false;
      continue;
    }
    if (is_space(c)) {
      space = true;
      ++at;
      continue;
    }
    if (c == '/' && at + 1 < text.size() && text[at + 1] == '*') {  // a comment reads as a space
      const std::size_t end = text.find("*/", at + 2);
      if (end == std::string::npos) malformed("a comment without its end");
      at = end + 2;
      space = true;
      continue;
    }
    if (c == ';') break;
    if (space && write > r.begin && is_letter(c) && (is_word_char(buf[write - 1]) || buf[write - 1] == ')'))
      buf[write++] = ' ';
    space = false;
    if (c == '#') {
      std::size_t j = at + 1;
      records.refs.push_back(entity_number(text, j));
      ++r.refs;
      emit(at, j - at);
      at = j;
      continue;
    }
    // A run of plain characters, copied at once.
    std::size_t end = at + 1;
    while (end < text.size() && is_plain(text[end])) ++end;
    emit(at, end - at);
    at = end;
  }
  r.size = write - r.begin;
  return at + 1;
}

std::size_t skip_space(const std::string& text, std::size_t at) {
  while (at < text.size() && is_space(text[at])) ++at;
  return at;
}

// The position just after the header's "DATA;" (outside strings).
std::size_t data_section_start(const std::string& text) {
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '\'') {
      const std::size_t end = text.find('\'', i + 1);
      if (end == std::string::npos) break;
      i = end;
      continue;
    }
    if (text.compare(i, 4, "DATA") == 0 && (i == 0 || !is_word_char(text[i - 1]))) {
      const std::size_t j = skip_space(text, i + 4);
      if (j < text.size() && text[j] == ';') return j + 1;
    }
  }
  malformed("no DATA section");
}

// The records of the DATA section starting at `at`, compacted in place in `text` (which the result owns).
Records read_records(std::string text, std::size_t at, std::size_t* end_of_data) {
  Records records;
  records.text = std::move(text);
  const std::string& text_ref = records.text;
  std::size_t write = at;
  // Reserved once (a record takes 40 to 70 bytes of OpenCASCADE's text, a reference 5 to 9): growing them took a
  // third of the reading.
  records.list.reserve((text_ref.size() - at) / 40);
  records.refs.reserve((text_ref.size() - at) / 8);
  long max_id = 0;
  while (true) {
    at = skip_space(text_ref, at);
    if (text_ref.compare(at, 6, "ENDSEC") == 0) break;
    if (at >= text_ref.size() || text_ref[at] != '#')
      malformed("a DATA section that is not a list of '#n=...;' records");
    Record r;
    std::size_t j = at + 1;
    r.id = entity_number(text_ref, j);
    j = skip_space(text_ref, j);
    if (j >= text_ref.size() || text_ref[j] != '=') malformed("a record without '#n ='");
    at = read_record_body(records, j + 1, write, r);
    max_id = std::max(max_id, r.id);
    records.list.push_back(std::move(r));
  }
  *end_of_data = at;
  // Writers number entities from 1 on; numbers far beyond the count would only make the table below huge.
  if (max_id > 16 * static_cast<long>(records.list.size()) + 1024) malformed("entity numbers far beyond their count");
  records.index_of_id.assign(max_id + 1, -1);
  for (std::size_t i = 0; i < records.list.size(); ++i) {
    int& slot = records.index_of_id[records.list[i].id];
    if (slot >= 0) malformed("#" + std::to_string(records.list[i].id) + " defined twice");
    slot = static_cast<int>(i);
  }
  return records;
}

// Marks the values, and among them those that only geometry and topology refer to.
void classify(Records& records) {
  std::vector<char> geometric(records.list.size(), 0);
  for (std::size_t i = 0; i < records.list.size(); ++i) {
    Record& r = records.list[i];
    const std::vector<std::string_view> words = keywords_of(records.body(r));
    const bool value = all_in(words, value_keywords());
    geometric[i] = value || all_in(words, value_keywords(), &geometry_keywords());
    r.may_share = value;
  }
  for (std::size_t i = 0; i < records.list.size(); ++i)
    if (!geometric[i])
      for (std::size_t k = 0; k < records.list[i].refs; ++k)
        records.list[records.index(records.ref(records.list[i], k))].may_share = false;
}

// "#id" appended to `out`.
void append_reference(std::string& out, long id) {
  char digits[24];
  digits[0] = '#';
  const auto end = std::to_chars(digits + 1, digits + sizeof digits, id).ptr;
  out.append(digits, end);
}

// The id of the entity written for record i: a value's first equal one (equal text once the values it refers to
// are replaced by theirs), any other record itself. Value chains are short (a pcurve's representation, curve,
// points), so the recursion is shallow; a cycle, which geometry never has, keeps its records.
long canonical(Records& records, std::unordered_map<std::string, long>& firsts, int i) {
  Record& r = records.list[i];
  if (r.canonical >= 0) return r.canonical;
  if (!r.may_share || r.visiting) return r.id;
  r.visiting = true;
  const std::string_view body = records.body(r);
  std::string key;
  key.reserve(body.size() + 8);
  std::size_t ref = 0;
  for (std::size_t k = 0; k < body.size();) {
    if (body[k] == '\'') {  // strings are copied whole: a '#' inside one is not a reference
      const std::size_t end = body.find('\'', k + 1) + 1;
      key.append(body, k, end - k);
      k = end;
    } else if (body[k] == '#') {
      append_reference(key, canonical(records, firsts, records.index(records.ref(r, ref++))));
      for (++k; k < body.size() && body[k] >= '0' && body[k] <= '9';) ++k;
    } else {
      const std::size_t end = std::min(body.find_first_of("'#", k), body.size());
      key.append(body, k, end - k);
      k = end;
    }
  }
  r.visiting = false;
  r.canonical = firsts.emplace(std::move(key), r.id).first->second;
  return r.canonical;
}

// Writes record r with its references renumbered, wrapping after a comma past 80 characters.
void write_record(const Records& records, const Record& r, const std::vector<long>& new_id,
                  const std::vector<long>& canonical_of, std::string& out) {
  std::size_t last_break = out.size();
  append_reference(out, new_id[records.index(r.id)]);
  out += '=';
  const std::string_view body = records.body(r);
  std::size_t ref = 0;
  for (std::size_t k = 0; k < body.size();) {
    const char c = body[k];
    if (c == '\'') {
      const std::size_t end = body.find('\'', k + 1) + 1;
      out.append(body, k, end - k);
      k = end;
    } else if (c == '#') {
      append_reference(out, new_id[records.index(canonical_of[records.index(records.ref(r, ref++))])]);
      for (++k; k < body.size() && body[k] >= '0' && body[k] <= '9';) ++k;
    } else if (c == ',') {
      out += ',';
      ++k;
      if (out.size() - last_break > 80) {
        out += '\n';
        last_break = out.size();
      }
    } else {
      const std::size_t end = std::min(body.find_first_of("'#,", k), body.size());
      out.append(body, k, end - k);
      k = end;
    }
  }
  out += ";\n";
}

}  // namespace

std::string share_equal_geometry(std::string text, StepSharing* sharing) {
  const std::size_t data = data_section_start(text), bytes_before = text.size();
  std::size_t end_of_data = 0;
  Records records = read_records(std::move(text), data, &end_of_data);
  const std::string_view tail = std::string_view(records.text).substr(end_of_data);  // not compacted over
  if (tail.find('#') != std::string_view::npos) malformed("records after the DATA section");
  classify(records);
  std::unordered_map<std::string, long> firsts;
  firsts.reserve(static_cast<std::size_t>(std::count_if(records.list.begin(), records.list.end(),
                                                        [](const Record& r) { return r.may_share; })));
  std::vector<long> canonical_of(records.list.size());
  for (std::size_t i = 0; i < records.list.size(); ++i)
    canonical_of[i] = canonical(records, firsts, static_cast<int>(i));
  firsts.clear();
  // The entities kept (those written for themselves) numbered from 1 in their order.
  std::vector<long> new_id(records.list.size(), 0);
  long next = 0;
  for (std::size_t i = 0; i < records.list.size(); ++i)
    if (canonical_of[i] == records.list[i].id) new_id[i] = ++next;
  std::string out;
  out.reserve(bytes_before / 2);
  out.append(records.text, 0, data);
  out += '\n';
  for (std::size_t i = 0; i < records.list.size(); ++i)
    if (new_id[i]) write_record(records, records.list[i], new_id, canonical_of, out);
  out.append(tail);
  if (sharing) {
    sharing->entities_before = records.list.size();
    sharing->entities_after = static_cast<std::size_t>(next);
    sharing->bytes_before = bytes_before;
    sharing->bytes_after = out.size();
  }
  return out;
}

}  // namespace steady
