/**
 * @file
 * Reading LS-DYNA keyword decks into keywords and cards (see the header).
 */
#include <anvil/mesh/keyword_file.h>
#include <anvil/mesh/mesh_file.h>
#include <anvil/utilities/input_error.h>
#include <anvil/utilities/text.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

namespace anvil::KeywordFile
{
  namespace
  {
    bool ends_with(const std::string &s, const std::string &tail)
    {
      return s.size() > tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
    }

    // A keyword as read, with the *CASE_BEGIN_n block it lies in (0: none).
    struct Read
    {
      Keyword keyword;
      long    block = 0;
    };

    struct Reader
    {
      std::vector<Read> read;
      bool              long_deck = false;
      long              block     = 0;
      bool              title_pending = false;

      void file(const std::string &name, const unsigned int depth, const Card *from)
      {
        std::ifstream in(name);
        if (!in)
          throw InputError((from ? from->where() : std::string()) + "deck '" + name +
                           "' cannot be opened");
        std::string  text;
        unsigned int number = 0;
        bool         include_next = false;
        while (std::getline(in, text))
          {
            ++number;
            if (!text.empty() && text.back() == '\r')
              text.pop_back();
            if (!text.empty() && text[0] == '$')
              continue;
            const Card card{text, name, number};
            if (include_next)
              {
                include_next = false;
                const std::string target = trim(text);
                if (target.empty())
                  throw InputError(card.where() + "*INCLUDE needs a file name on this card");
                if (depth >= 10)
                  throw InputError(card.where() + "*INCLUDE nested more than 10 deep");
                std::filesystem::path path(target);
                if (path.is_relative())
                  {
                    const auto beside = std::filesystem::path(name).parent_path() / path;
                    if (std::filesystem::exists(beside) || !std::filesystem::exists(path))
                      path = beside;
                  }
                if (!std::filesystem::is_regular_file(path))
                  throw InputError(card.where() + "*INCLUDE: file '" + printable_excerpt(target) +
                                   "' does not exist (relative to the including deck's folder)");
                file(path.string(), depth + 1, &card);
                continue;
              }
            if (!text.empty() && text[0] == '*')
              {
                std::string head = text.substr(1);
                const auto  cut  = head.find_first_of(" \t,");
                std::string rest = cut == std::string::npos ? std::string() : head.substr(cut);
                std::string name_ = MeshFile::key(cut == std::string::npos ? head : head.substr(0, cut));
                Keyword     kw;
                kw.line        = card;
                kw.long_format = long_deck;
                if (!name_.empty() && (name_.back() == '+' || name_.back() == '-'))
                  {
                    kw.long_format = name_.back() == '+';
                    name_.pop_back();
                  }
                else if (trim(rest) == "+" || trim(rest) == "-")
                  kw.long_format = trim(rest) == "+";
                if (!name_.empty() && name_.back() == '%')
                  throw InputError(card.where() + "*" + name_ +
                                   ": the I10 format ('%') is not supported (allowed: standard, "
                                   "long '+' and free format with commas)");
                if (name_ == "END")
                  return;
                if (name_ == "KEYWORD")
                  {
                    const std::string r = MeshFile::key(rest);
                    const auto        at = r.find("LONG");
                    if (at != std::string::npos)
                      {
                        const auto eq = r.find('=', at);
                        long_deck = eq != std::string::npos &&
                                    trim(r.substr(eq + 1)).substr(0, 1) == "Y";
                      }
                    continue;
                  }
                if (name_ == "INCLUDE")
                  {
                    include_next = true;
                    continue;
                  }
                if (name_.rfind("CASE_BEGIN_", 0) == 0 || name_.rfind("CASE_END_", 0) == 0)
                  {
                    const bool        begin = name_[5] == 'B';
                    const std::string id    = name_.substr(begin ? 11 : 9);
                    char             *end   = nullptr;
                    const long        n     = std::strtol(id.c_str(), &end, 10);
                    if (id.empty() || *end != '\0' || n <= 0)
                      throw InputError(card.where() + "*" + name_ + ": expected a positive block number");
                    if (begin == (block != 0) || (!begin && n != block))
                      throw InputError(card.where() + "*" + name_ + " without its " +
                                       (begin ? "*CASE_END of block " + std::to_string(block) :
                                                std::string("*CASE_BEGIN")));
                    block = begin ? n : 0;
                    continue;
                  }
                // '_TITLE' and '_ID' add a first card (a title, or an id and a
                // heading) that names but does not change anything.
                for (const std::string option : {"_TITLE", "_ID"})
                  if (ends_with(name_, option))
                    {
                      name_.erase(name_.size() - option.size());
                      title_pending = true;
                    }
                kw.name = name_;
                read.push_back({kw, block});
                continue;
              }
            if (read.empty())
              {
                if (trim(text).empty())
                  continue;
                throw InputError(card.where() + "a card before the first keyword");
              }
            if (title_pending)
              {
                read.back().keyword.title = trim(text);
                title_pending             = false;
                continue;
              }
            read.back().keyword.cards.push_back(card);
          }
        if (include_next)
          throw InputError("deck '" + name + "' ends after *INCLUDE without a file name");
      }
    };
  } // namespace


  std::string Card::where() const
  {
    return "deck '" + file + "', line " + std::to_string(line) + ": ";
  }


  std::vector<std::string> Keyword::fields(const unsigned int c, const std::vector<unsigned int> &widths) const
  {
    std::vector<std::string> out;
    if (c >= cards.size())
      return std::vector<std::string>(widths.size());
    const std::string &t = cards[c].text;
    if (t.find(',') != std::string::npos)
      {
        std::string::size_type start = 0;
        while (true)
          {
            const auto comma = t.find(',', start);
            out.push_back(trim(t.substr(start, comma == std::string::npos ? std::string::npos : comma - start)));
            if (comma == std::string::npos)
              break;
            start = comma + 1;
          }
      }
    else
      {
        std::string::size_type at = 0;
        for (const unsigned int w0 : widths)
          {
            const unsigned int w = long_format ? 20 : w0;
            out.push_back(at < t.size() ? trim(t.substr(at, w)) : std::string());
            at += w;
          }
      }
    out.resize(std::max(out.size(), widths.size()));
    return out;
  }


  std::vector<std::string> Keyword::fields(const unsigned int c) const
  {
    return fields(c, std::vector<unsigned int>(8, 10));
  }


  double real(const std::string &field, const Card &card, const std::string &what, const double fallback)
  {
    std::string s = trim(field);
    if (s.empty())
      return fallback;
    for (auto &ch : s)
      if (ch == 'd' || ch == 'D')
        ch = 'e';
    const auto bad = [&]() {
      return InputError(card.where() + what + ": '" + printable_excerpt(field) + "' is not a number");
    };
    char  *end = nullptr;
    errno      = 0;
    double value = std::strtod(s.c_str(), &end);
    if (*end != '\0')
      {
        // Fortran's E-less exponent: '7.34000-4', '1.0+3'.
        const auto sign = s.find_last_of("+-");
        if (sign == std::string::npos || sign == 0 || s.find_first_of("eE") != std::string::npos)
          throw bad();
        const std::string mantissa = s.substr(0, sign), exponent = s.substr(sign);
        if (exponent.size() < 2 ||
            !std::all_of(exponent.begin() + 1, exponent.end(), [](char c) { return std::isdigit(c); }))
          throw bad();
        value = std::strtod((mantissa + "e" + exponent).c_str(), &end);
        if (*end != '\0')
          throw bad();
      }
    if (!std::isfinite(value) || errno == ERANGE)
      throw InputError(card.where() + what + ": '" + printable_excerpt(field) +
                       "' is not a finite number of double precision");
    return value;
  }


  long integer(const std::string &field, const Card &card, const std::string &what, const long fallback)
  {
    const std::string s = trim(field);
    if (s.empty())
      return fallback;
    char      *end   = nullptr;
    errno            = 0;
    const long value = std::strtol(s.c_str(), &end, 10);
    if (*end == '\0' && errno == 0 && std::labs(value) < 2000000000L)
      return value;
    // '1.' or '1.0' for an integer.
    const double r = real(field, card, what);
    if (r == std::floor(r) && std::abs(r) < 2e9)
      return static_cast<long>(r);
    throw InputError(card.where() + what + ": '" + printable_excerpt(field) +
                     "' is not an integer (below 2e9 in magnitude)");
  }


  long &chosen_case()
  {
    static long id = 0;
    return id;
  }


  Keywords read(const std::string &file_name, const long case_id)
  {
    Reader reader;
    reader.file(file_name, 0, nullptr);
    if (reader.block != 0)
      throw InputError("deck '" + file_name + "': *CASE_BEGIN_" + std::to_string(reader.block) +
                       " is never closed by its *CASE_END");

    // *CASE: an id and job name, the command line of the case, then the
    // numbers of the *CASE_BEGIN_n blocks that count in it.
    Keywords                            deck;
    std::map<long, std::set<long>>      blocks_of;
    for (const auto &r : reader.read)
      if (r.keyword.name == "CASE")
        {
          const auto &kw = r.keyword;
          if (kw.cards.empty())
            throw InputError(kw.line.where() + "*CASE needs a card 'CASEID JOBID'");
          const auto head = kw.fields(0, {10, 70});
          const long id   = integer(head[0], kw.cards[0], "*CASE CASEID");
          deck.cases.emplace_back(id, head[1]);
          for (unsigned int c = 2; c < kw.cards.size(); ++c)
            {
              const auto f = kw.fields(c);
              bool       numbers = true;
              for (const auto &x : f)
                numbers = numbers && std::all_of(x.begin(), x.end(), [](char ch) { return std::isdigit(ch); });
              if (numbers)
                for (const auto &x : f)
                  if (!x.empty())
                    blocks_of[id].insert(std::stol(x));
            }
        }
    if (case_id != 0 && blocks_of.count(case_id) == 0 &&
        std::none_of(deck.cases.begin(), deck.cases.end(), [&](const auto &c) { return c.first == case_id; }))
      throw InputError("deck '" + file_name + "': --case " + std::to_string(case_id) +
                       ": the deck defines no such *CASE" +
                       (deck.cases.empty() ? std::string(" (it defines none)") : std::string()));
    const auto &active = blocks_of[case_id];
    for (auto &r : reader.read)
      if (r.block == 0 || active.count(r.block))
        deck.keywords.push_back(std::move(r.keyword));
    return deck;
  }


  std::vector<NodeVelocityGroup> node_velocity_groups(const Keyword &kw)
  {
    std::vector<NodeVelocityGroup>                           groups;
    std::map<std::pair<std::array<double, 6>, long>, std::size_t> index;
    for (unsigned int c = 0; c < kw.cards.size(); ++c)
      {
        const Card &card = kw.cards[c];
        if (card.blank())
          continue;
        const auto            f = kw.fields(c);
        std::array<double, 6> v;
        for (unsigned int d = 0; d < 6; ++d)
          v[d] = real(f[1 + d], card, "*" + kw.name + " " + (d < 3 ? "V" : "VR") + char('X' + d % 3));
        const long icid = integer(f[7], card, "*" + kw.name + " ICID");
        const auto [at, added] = index.emplace(std::make_pair(v, icid), groups.size());
        if (added)
          groups.push_back({v, icid, {}, {}});
        groups[at->second].nids.push_back(integer(f[0], card, "*" + kw.name + " NID"));
        groups[at->second].cards.push_back(&card);
      }
    return groups;
  }
} // namespace anvil::KeywordFile
