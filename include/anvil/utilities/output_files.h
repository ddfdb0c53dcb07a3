/**
 * @file
 * Results that stay consistent on disk: CSV histories written in whole
 * rows, files replaced by renaming, write errors reported with the file and
 * the cause.
 */
#pragma once

#include <fstream>
#include <functional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace anvil
{
  /**
   * The results could not be written (disk full, file-size limit, no
   * permission). main() prints it as one line and exits with status 4.
   */
  class OutputError : public std::runtime_error
  {
  public:
    explicit OutputError(const std::string &message)
      : std::runtime_error(message)
    {}
  };

  /**
   * Write @p text to @p path under a temporary name, then rename it: a
   * reader never sees half a file, and the old file stays until the new one
   * is complete. Throws OutputError naming the file and the cause.
   */
  void write_atomically(const std::string &path, const std::string &text);

  /** The same with the text written to a stream by @p write (a large file
      that need not be held in memory whole). */
  void write_atomically(const std::string &path, const std::function<void(std::ostream &)> &write);

  /**
   * A CSV history: rows are composed in memory and reach the file only
   * whole, when flush() writes everything held in one piece. A run killed at
   * any moment leaves complete rows.
   */
  class HistoryFile
  {
  public:
    HistoryFile() = default;
    explicit HistoryFile(const std::string &path)
    {
      open(path);
    }

    /** Create (truncate) the file; OutputError if it cannot be opened. */
    void open(const std::string &path);

    bool is_open() const
    {
      return out.is_open();
    }

    /** Bytes of whole rows on disk. */
    long bytes_written() const
    {
      return written;
    }

    const std::string &file() const
    {
      return path;
    }

    /** Continue a file a checkpoint recorded at @p length bytes: cut it back
        to that length and append. */
    void resume(const std::string &path, long length);

    template <typename T>
    HistoryFile &operator<<(const T &x)
    {
      buffer << x;
      return *this;
    }

    /** Write the rows held so far; an empty string on success, else the
        file and the cause. */
    std::string flush();

  private:
    std::string        path;
    std::ofstream      out;
    /** Bytes of whole rows on disk. */
    long               written = 0;
    std::ostringstream buffer;
  };


  /** Pointers to each of @p files (a family's or postprocessor's list). */
  inline std::vector<HistoryFile *> pointers_to(std::vector<HistoryFile> &files)
  {
    std::vector<HistoryFile *> list;
    for (auto &f : files)
      list.push_back(&f);
    return list;
  }
} // namespace anvil
