// Seeded mutations of an input file, as a person, a full disk or a broken program would damage it,
// for the fuzz tests of every way in (case, drawing, sweep and catalogue files): a line replaced
// by a troublesome value, dropped, repeated or swapped with the next, a number replaced, a byte
// changed, the text cut short. The same seed gives the same mutants on every machine.
#pragma once

#include <cstdint>
#include <random>
#include <string>
#include <vector>

namespace masonry::test {

class Mutator {
 public:
  explicit Mutator(uint32_t seed) : rng_(seed) {}

  // One to three mutations of `text`.
  std::string operator()(const std::string& text) {
    std::string t = text;
    const int n = 1 + pick(3);
    for (int k = 0; k < n; ++k) t = once(t);
    return t;
  }

 private:
  // Values that broke or fooled readers before: non-numbers, numbers beyond every range, counts
  // at the integer limits, decimal commas, trailing text, structure words, control bytes,
  // bytes that are not UTF-8, a very long word.
  const std::vector<std::string>& values() const {
    static const std::vector<std::string> v = {
        "",
        "nan",
        "-nan",
        "inf",
        "-inf",
        "1e309",
        "-1e309",
        "1e308",
        "-1e308",
        "1e-320",
        "99999999999",
        "2147483647",
        "-2147483648",
        "4294967296",
        "32768",
        "-32769",
        "-1",
        "0",
        "1",
        "3",
        "1,5",
        "0.4  junk",
        "abc",
        "XYZ",
        "0x10",
        "+",
        "-",
        ".",
        "1e",
        "  7  ",
        "\t",
        "1e5",
        "-1e300",
        "0.0000001",
        "SECTION",
        "ENDSEC",
        "EOF",
        "POLYLINE",
        "VERTEX",
        "SEQEND",
        "LWPOLYLINE",
        "TEXT",
        "MTEXT",
        "HEADER",
        "ENTITIES",
        "$INSUNITS",
        "10",
        "20",
        "42",
        "90",
        "70",
        "5",
        "8",
        "\x1b[31m",
        "\xff\xfe",
        "\xc3",
        "{",
        "}",
        "[",
        "]",
        "\"",
        ",",
        ":",
        "null",
        "true",
        "[]",
        "{}",
        "\"x\"",
        std::string(5000, 'A'),
        "\"step\": 0.5,",
        "\"format\": \"x\",",
    };
    return v;
  }
  int pick(int n) { return static_cast<int>(rng_() % static_cast<uint32_t>(n)); }
  const std::string& value() { return values()[pick(static_cast<int>(values().size()))]; }

  static std::vector<std::string> lines(const std::string& t) {
    std::vector<std::string> out(1);
    for (char ch : t) {
      if (ch == '\n')
        out.emplace_back();
      else
        out.back() += ch;
    }
    return out;
  }
  static std::string join(const std::vector<std::string>& ls) {
    std::string t;
    for (size_t k = 0; k < ls.size(); ++k) t += (k ? "\n" : "") + ls[k];
    return t;
  }

  std::string once(const std::string& t) {
    if (t.empty()) return value();
    std::vector<std::string> ls = lines(t);
    const size_t i = static_cast<size_t>(pick(static_cast<int>(ls.size())));
    switch (pick(8)) {
      case 0: ls[i] = value(); break;
      case 1: ls.erase(ls.begin() + static_cast<long>(i)); break;
      case 2: ls.insert(ls.begin() + static_cast<long>(i), ls[i]); break;
      case 3:
        if (i + 1 < ls.size()) std::swap(ls[i], ls[i + 1]);
        break;
      case 4: ls.insert(ls.begin() + static_cast<long>(i), value()); break;
      case 5: {  // a number inside the line replaced
        std::string& l = ls[i];
        const size_t a = l.find_first_of("0123456789");
        if (a == std::string::npos) break;
        const size_t b = l.find_first_not_of("0123456789.eE+-", a);
        l = l.substr(0, a) + value() + (b == std::string::npos ? "" : l.substr(b));
        break;
      }
      case 6: {  // a byte changed
        std::string s = join(ls);
        s[static_cast<size_t>(pick(static_cast<int>(s.size())))] = static_cast<char>(rng_() & 0xff);
        return s;
      }
      default: {  // cut short
        const std::string s = join(ls);
        return s.substr(0, static_cast<size_t>(pick(static_cast<int>(s.size()))));
      }
    }
    return join(ls);
  }

  std::mt19937 rng_;
};

}  // namespace masonry::test
