/**
 * @file
 * Writing a scene's text for the deck translators: 'set' lines inside
 * subsections, each remembering the deck line it came from.
 */
#pragma once

#include <anvil/deck/deck.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace anvil::Deck
{
  class SceneWriter
  {
  public:
    /** The deck line that the next lines come from. */
    void from(const std::string &file, const int line)
    {
      origin = {file, line};
    }

    void comment(const std::string &text)
    {
      add("# " + text);
    }
    void enter(const std::string &subsection)
    {
      add("subsection " + subsection);
      ++depth;
    }
    void leave()
    {
      --depth;
      add("end");
    }
    void set(const std::string &entry, const std::string &value)
    {
      add("set " + entry + " = " + value);
    }
    void set_entry(const std::string &entry, const std::string &value)
    {
      set(entry, value);
    }
    void set(const std::string &entry, const double value)
    {
      set(entry, number(value));
    }
    void blank()
    {
      add("");
    }

    /** Shortest text that reads back as the same double. */
    static std::string number(const double x)
    {
      char buffer[40];
      for (int precision = 6; precision <= 17; ++precision)
        {
          std::snprintf(buffer, sizeof(buffer), "%.*g", precision, x);
          if (std::strtod(buffer, nullptr) == x)
            break;
        }
      return buffer;
    }
    static std::string vector(const double x, const double y, const double z)
    {
      return number(x) + ", " + number(y) + ", " + number(z);
    }

    /** A boundary condition on the nodes of a mesh file's node set: the
        directions @p dofs held, at rest or (@p velocity) at @p value. */
    void node_set_condition(const std::string &name, const std::string &body, const std::string &set,
                            const std::array<bool, 3> &dofs, const bool velocity, const double value[3])
    {
      blank();
      enter("Boundary condition " + name);
      set_entry("Body", body);
      set_entry("Selection", "node set");
      set_entry("Node sets", set);
      std::string components;
      for (unsigned int d = 0; d < 3; ++d)
        if (dofs[d])
          components += std::string(components.empty() ? "" : ", ") + char('x' + d);
      set_entry("Components", components);
      if (velocity)
        {
          set_entry("Type", "velocity");
          set_entry("Velocity", vector(value[0], value[1], value[2]));
        }
      leave();
    }

    /** Notes for the two warnings, each listed once. */
    void ignore(const std::string &what)
    {
      if (ignored_set.insert(what).second)
        ignored.push_back(what);
    }
    void differ(const std::string &what)
    {
      if (differs_set.insert(what).second)
        differs.push_back(what);
    }

    Translation result() const
    {
      Translation t;
      t.text   = text;
      t.origin = origins;
      for (const auto &i : ignored)
        t.ignored += (t.ignored.empty() ? "" : ", ") + i;
      for (const auto &d : differs)
        t.differs += (t.differs.empty() ? "" : "; ") + d;
      return t;
    }

  private:
    void add(const std::string &line)
    {
      text += std::string(2 * depth, ' ') + line + '\n';
      origins.push_back(origin);
    }

    std::string                              text;
    std::vector<std::pair<std::string, int>> origins;
    std::pair<std::string, int>              origin{"", 0};
    int                                      depth = 0;
    std::vector<std::string>                 ignored, differs;
    std::set<std::string>                    ignored_set, differs_set;
  };
} // namespace anvil::Deck
