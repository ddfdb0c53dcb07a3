/**
 * @file
 * LS-DYNA keyword decks read as LS-DYNA reads them: keywords and their
 * cards, '$' comments, *INCLUDE, *CASE blocks, fixed fields (values may run
 * together with no blank between them), free format with commas, long
 * format ('*KEYWORD LONG=Y', or '+' after a keyword), lower case, and reals
 * written without the E ('7.34000-4'). The mesh reader and the deck
 * translator both read a deck through this.
 */
#pragma once

#include <array>
#include <string>
#include <vector>

namespace anvil::KeywordFile
{
  /** One card (data line) and where it was read. */
  struct Card
  {
    std::string  text;
    std::string  file;
    unsigned int line = 0;

    /** "deck 'FILE', line N: " for messages. */
    std::string where() const;
    /** Nothing but blanks and tabs (a card a keyword's list skips). */
    bool blank() const
    {
      return text.find_first_not_of(" \t") == std::string::npos;
    }
  };

  /** One keyword with its cards. */
  struct Keyword
  {
    /** Upper case, without the '*', the options '_TITLE' and '_ID' and a
        trailing comment ("*ELEMENT_SOLID (ten nodes format)"): e.g.
        "MAT_PLASTIC_KINEMATIC". */
    std::string name;
    /** The keyword's line as written. */
    Card        line;
    /** Text of the title or heading card that '_TITLE'/'_ID' added (its
        cards are not in @p cards). */
    std::string title;
    bool        long_format = false;
    std::vector<Card> cards;

    /** The fields of card @p c: between commas in free format, else in
        columns of the widths given (all 20 wide in long format). A field
        beyond the card's end is empty. */
    std::vector<std::string> fields(unsigned int c, const std::vector<unsigned int> &widths) const;
    /** ... with every field 10 wide (20 long): the common card. */
    std::vector<std::string> fields(unsigned int c) const;
  };

  /** A deck: its keywords in order, with *INCLUDE files in place and the
      *CASE blocks of the chosen case. */
  struct Keywords
  {
    std::vector<Keyword> keywords;
    /** The cases the deck defines (*CASE): id and job name. */
    std::vector<std::pair<long, std::string>> cases;
  };

  /** Read @p file_name. @p case_id: the case whose *CASE_BEGIN_n blocks
      count (0: none; a deck that defines cases then needs one chosen,
      which the translator says). Throws InputError with file and line. */
  Keywords read(const std::string &file_name, long case_id);

  /** The case chosen on the command line ('anvil DECK.k --case ID'), 0 if
      none; every reader of the run's deck reads with it. */
  long &chosen_case();

  /** A real field as LS-DYNA reads it (empty: @p fallback; '1.5-3' is
      1.5e-3). */
  double real(const std::string &field, const Card &card, const std::string &what, double fallback = 0);
  /** An integer field (empty: @p fallback). */
  long integer(const std::string &field, const Card &card, const std::string &what, long fallback = 0);

  /** The cards of an *INITIAL_VELOCITY_NODE (NID VX VY VZ VXR VYR VZR
      ICID) grouped by their values, in the order of each group's first
      card: the mesh reader makes a node set of each group, the deck
      translator gives their velocity to the parts they hold. */
  struct NodeVelocityGroup
  {
    /** VX VY VZ VXR VYR VZR. */
    std::array<double, 6> values;
    long                  icid;
    std::vector<long>     nids;
    /** The card of each node. */
    std::vector<const Card *> cards;
  };
  std::vector<NodeVelocityGroup> node_velocity_groups(const Keyword &kw);

  /** The name of the node set of group @p g of the @p k-th
      *INITIAL_VELOCITY_NODE of a deck (both counted from 0). */
  inline std::string node_velocity_set(const unsigned int k, const unsigned int g)
  {
    return "INITIAL_VELOCITY_NODE" + std::to_string(k) + "_" + std::to_string(g);
  }
} // namespace anvil::KeywordFile
