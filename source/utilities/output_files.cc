#include <anvil/utilities/output_files.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

#include <unistd.h>

namespace anvil
{
  namespace
  {
    std::string cause()
    {
      return errno != 0 ? std::strerror(errno) : "the write failed";
    }
  } // namespace


  void write_atomically(const std::string &path, const std::string &text)
  {
    write_atomically(path, [&text](std::ostream &out) { out.write(text.data(), text.size()); });
  }


  void write_atomically(const std::string &path, const std::function<void(std::ostream &)> &write)
  {
    const std::string tmp = path + ".tmp";
    errno                 = 0;
    {
      std::ofstream out(tmp);
      if (!out)
        throw OutputError("cannot create " + tmp + ": " + cause());
      write(out);
      out.flush();
      if (!out)
        throw OutputError("cannot write " + tmp + ": " + cause());
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0)
      throw OutputError("cannot rename " + tmp + " to " + path + ": " + cause());
  }


  void HistoryFile::open(const std::string &file)
  {
    path  = file;
    errno = 0;
    out.open(file);
    if (!out)
      throw OutputError("cannot create " + file + ": " + cause());
  }


  void HistoryFile::resume(const std::string &file, const long length)
  {
    path  = file;
    errno = 0;
    if (::truncate(file.c_str(), length) != 0)
      throw OutputError("cannot cut " + file + " back to its length at the checkpoint: " + cause());
    out.open(file, std::ios::app);
    if (!out)
      throw OutputError("cannot open " + file + " to continue it: " + cause());
    written = length;
  }


  std::string HistoryFile::flush()
  {
    const std::string text = buffer.str();
    if (text.empty() || !out.is_open())
      return "";
    buffer.str("");
    errno = 0;
    out.write(text.data(), text.size());
    out.flush();
    if (!out)
      {
        // Keep the rows that were whole: cut the file back to them.
        const std::string failure = "cannot write " + path + ": " + cause();
        out.close();
        if (::truncate(path.c_str(), written) != 0)
          return failure + " (and it could not be cut back to its last whole row)";
        return failure;
      }
    written += text.size();
    return "";
  }
} // namespace anvil
