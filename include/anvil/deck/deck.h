/**
 * @file
 * Decks of other codes as Anvil scenes: an LS-DYNA keyword deck (.k, .key,
 * .dyn) or a whole ABAQUS/Explicit deck (.inp) becomes the text of the
 * equivalent scene, its mesh read from the deck itself. 'anvil DECK' runs
 * that scene; 'anvil --translate DECK' prints it.
 */
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace anvil::Deck
{
  /** The scene a deck translates to. */
  struct Translation
  {
    /** The scene's text (parameter-file syntax). */
    std::string text;
    /** For each line of @p text: the deck file and line it came from. */
    std::vector<std::pair<std::string, int>> origin;
    /** What the deck holds that Anvil answers its own way or that changes
        nothing of the physics (output requests, titles), for one warning;
        empty if nothing. */
    std::string ignored;
    /** Where Anvil's model differs from the other code's for this deck
        (e.g. a penalty wall where LS-DYNA constrains), for one warning;
        empty if nothing. */
    std::string differs;
  };

  /** Whether @p file is a deck (by its extension: .k, .key, .dyn; .inp). */
  bool is_deck(const std::string &file);

  /** Translate @p file. @p mesh_path: how the scene names the deck as its
      mesh file (relative to the scene's folder: the deck's own name when
      the scene is the deck, the path given when the scene is printed).
      Throws InputError (file, line, what is not supported and what is)
      for anything that changes the physics and that Anvil cannot do. */
  Translation translate(const std::string &file, const std::string &mesh_path);

  Translation translate_keyword_deck(const std::string &file, const std::string &mesh_path);
  Translation translate_abaqus_deck(const std::string &file, const std::string &mesh_path);
} // namespace anvil::Deck
