#include "support/lattice_text.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <optional>

namespace boxgen::support {

namespace {

constexpr std::size_t kMaxEchoedChars = 40;  // how much of a bad token a message repeats

[[noreturn]] void fail(const std::string& message) { throw TextError(message); }

std::string entries(std::size_t count) {
  return fmt::format("{} {}", count, count == 1 ? "entry" : "entries");
}

// Parses one integer token [+-]digits without overflow: more than 18 significant digits
// saturate at 10^18, which every caller rejects as too large while naming the token.
std::optional<std::int64_t> parse_integer(std::string_view token) {
  std::string_view digits = token;
  bool negative = false;
  if (!digits.empty() && (digits.front() == '+' || digits.front() == '-')) {
    negative = digits.front() == '-';
    digits.remove_prefix(1);
  }
  if (digits.empty()) return std::nullopt;
  for (char c : digits)
    if (c < '0' || c > '9') return std::nullopt;
  while (digits.size() > 1 && digits.front() == '0') digits.remove_prefix(1);
  constexpr std::int64_t kSaturated = 1'000'000'000'000'000'000;
  std::int64_t value = 0;
  if (digits.size() > 18) {
    value = kSaturated;
  } else {
    for (char c : digits) value = value * 10 + (c - '0');
  }
  return negative ? -value : value;
}

// Checks that all rows have one length, 2 or 3.
void check_common_dimension(const IntegerRows& rows, const RowSyntax& syntax) {
  const auto n = rows.front().size();
  if (n != 2 && n != 3)
    fail(fmt::format(
        "invalid {0}: {1} 1 has {2}, but {1}s must have 2 or 3 entries (2-D or 3-D){3}",
        syntax.list, syntax.row, entries(n),
        std::string(syntax.list) == "SPEC"
            ? "; a SPEC lists the directions (the columns of Xi), one per ';'"
            : "; --lattice takes the rows of G (its columns are the lattice basis), one per ';'"));
  for (std::size_t r = 1; r < rows.size(); ++r)
    if (rows[r].size() != n)
      fail(fmt::format(
          "invalid {0}: {1} {2} has {3} but {1} 1 has {4}; all must have the same dimension",
          syntax.list, syntax.row, r + 1, entries(rows[r].size()), n));
}

}  // namespace

bool is_blank(char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; }

std::string lower(std::string_view text) {
  std::string out(text);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

std::string_view trim(std::string_view text) {
  while (!text.empty() && is_blank(text.front())) text.remove_prefix(1);
  while (!text.empty() && is_blank(text.back())) text.remove_suffix(1);
  return text;
}

std::string echo(std::string_view text) {
  std::string out;
  for (char c : text.substr(0, kMaxEchoedChars)) out.push_back(c >= 0x20 && c <= 0x7e ? c : '?');
  if (text.size() > kMaxEchoedChars) out += "...";
  return out;
}

IntegerRows parse_rows(std::string_view text, const RowSyntax& syntax, std::size_t max_rows) {
  std::vector<std::string_view> pieces;
  for (;;) {
    auto semi = text.find(';');
    pieces.push_back(text.substr(0, semi));
    if (semi == std::string_view::npos) break;
    text.remove_prefix(semi + 1);
  }
  while (!pieces.empty() && trim(pieces.back()).empty()) pieces.pop_back();
  if (pieces.empty())
    fail(fmt::format("empty {}: expected integer {}s separated by ';', such as '1,0; 0,1; 1,1'",
                     syntax.list, syntax.row));
  if (pieces.size() > max_rows)
    fail(
        fmt::format("{} {}s given: at most {} are supported", pieces.size(), syntax.row, max_rows));

  IntegerRows rows;
  for (std::size_t r = 0; r < pieces.size(); ++r) {
    const std::string where = fmt::format("{} {}", syntax.row, r + 1);
    std::string_view row = trim(pieces[r]);
    if (row.empty())
      fail(fmt::format("invalid {}: {} is empty (two ';' in a row?)", syntax.list, where));
    std::vector<std::int64_t> values;
    for (;;) {
      auto comma = row.find(',');
      std::string_view part = row.substr(0, comma);
      bool any = false;
      // Within a comma-separated part, blanks separate further entries.
      for (;;) {
        part = trim(part);
        if (part.empty()) break;
        auto end = std::find_if(part.begin(), part.end(), is_blank) - part.begin();
        std::string_view token = part.substr(0, static_cast<std::size_t>(end));
        part.remove_prefix(static_cast<std::size_t>(end));
        auto value = parse_integer(token);
        if (!value)
          fail(fmt::format("invalid {}: {} has the entry '{}', which is not an integer",
                           syntax.list, where, echo(token)));
        if (std::llabs(*value) > syntax.max_abs)
          fail(fmt::format(
              "{} has the entry '{}', which is too large {}: entries must be at most {} in "
              "magnitude",
              where, echo(token), syntax.too_large, syntax.max_abs));
        values.push_back(*value);
        any = true;
      }
      if (!any)
        fail(fmt::format("invalid {}: {} ('{}') has an empty entry (stray ',')", syntax.list, where,
                         echo(trim(pieces[r]))));
      if (comma == std::string_view::npos) break;
      row.remove_prefix(comma + 1);
    }
    rows.push_back(std::move(values));
  }
  check_common_dimension(rows, syntax);
  return rows;
}

LatticeText parse_lattice_text(std::string_view text, int dimension, std::string_view because,
                               std::int64_t max_entry) {
  const std::string_view t = trim(text);
  if (t.empty())
    fail(
        "empty lattice: expected bcc, fcc, cartesian or the rows of G such as '1,1,0; 1,0,1; "
        "0,1,1'");
  if (std::isalpha(static_cast<unsigned char>(t.front()))) {
    std::string name = lower(t);
    if (name != "cartesian" && name != "bcc" && name != "fcc")
      fail(fmt::format(
          "unknown lattice '{}': expected bcc, fcc, cartesian or the rows of G such as '1,1,0; "
          "1,0,1; 0,1,1'",
          echo(t)));
    if (name != "cartesian" && dimension != 3)
      fail(fmt::format("the {} lattice is 3-dimensional but {}", name, because));
    return {std::move(name), {}};
  }
  const RowSyntax syntax{"lattice", "lattice row", max_entry, "for a lattice generator"};
  IntegerRows rows = parse_rows(t, syntax, 3);
  const std::size_t n = rows.front().size();
  if (static_cast<int>(n) != dimension)
    fail(fmt::format("the lattice is {}-dimensional but {}", n, because));
  if (rows.size() != n)
    fail(fmt::format(
        "the lattice generator must be square: got {} rows of {} entries, expected {} rows",
        rows.size(), n, n));
  return {{}, std::move(rows)};
}

}  // namespace boxgen::support
