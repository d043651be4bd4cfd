// An output folder written all or nothing, for the commands that take --out DIR.
//
//   auto out = dstrans::output_dir::open("out/pane", "frame.json");   // checked before any work is done
//   if (!out) return fail(out.error());
//   out->add("final.png", png_bytes);            // written and closed in a staging folder inside DIR
//   out->set_manifest({{"technique", "interlaced"}});   // frame.json: its keys and "files", written last
//   if (auto ok = out->commit(); !ok) return fail(ok.error());   // renamed into DIR, or nothing new
//
// The rules: a file of DIR is replaced only when the previous run's manifest (DIR/<manifest>'s "files")
// lists it, so a user's own files are never overwritten; nothing that is not a plain file (a symbolic
// link, a device, a folder) is ever replaced or written through; the previous run's files that this run
// does not write are removed, so the folder holds one run's outputs; a failed write, a full disk or an
// error before commit() leaves DIR as it was (the staging folder is removed; a run killed outright leaves
// its .dstrans-* staging folder, which later runs ignore).
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <dstrans/result.hpp>

namespace dstrans {

class output_dir {
 public:
  // DIR made if missing (its parents too), checked to be a writable folder, and a staging folder made in it.
  static result<output_dir> open(const std::string& dir, const std::string& manifest);
  output_dir(output_dir&&) noexcept;
  output_dir& operator=(output_dir&&) = delete;
  ~output_dir();

  // The staging folder: a writer that makes its own files (a script) writes them there, then calls adopt.
  const std::string& staging() const { return staging_; }
  // Writes `bytes` as file `name` (a plain name, no folders) into the staging folder, checked to the close.
  result<bool> add(const std::string& name, const std::string& bytes);
  // Takes the files a writer put into the staging folder as outputs.
  result<bool> adopt();
  // The manifest: `fields` and "files" (every output, the manifest included), written last by commit().
  void set_manifest(nlohmann::ordered_json fields) { manifest_fields_ = std::move(fields); }
  // Moves every output into DIR, the manifest last, and removes the previous run's files not written again.
  result<bool> commit();

  const std::string& dir() const { return dir_; }

 private:
  output_dir(std::string dir, std::string manifest, std::string staging, std::vector<std::string> previous);
  std::string dir_, manifest_, staging_;
  std::vector<std::string> previous_, files_;
  nlohmann::ordered_json manifest_fields_ = nlohmann::ordered_json::object();
};

}  // namespace dstrans
