// Implements output_dir.hpp with POSIX calls: a staging folder made by mkdtemp inside DIR, files created
// there with O_EXCL | O_NOFOLLOW and closed with their errors checked, then renamed into DIR.
#include "output_dir.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

#include <dirent.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace dstrans {

namespace {

std::string why() { return std::strerror(errno); }

// What is at `path`, without following a symbolic link: 0 nothing, 1 a plain file, 2 anything else.
int what_is(const std::string& path) {
  struct stat st {};
  if (lstat(path.c_str(), &st) != 0) return 0;
  return S_ISREG(st.st_mode) ? 1 : 2;
}

bool plain_name(const std::string& name) {
  return !name.empty() && name != "." && name != ".." && name.find('/') == std::string::npos &&
         name.rfind(".dstrans-", 0) != 0;
}

// The files the previous run listed in DIR/manifest, if that manifest is one of ours (a JSON object);
// `ours` says whether it is.
std::vector<std::string> previous_files(const std::string& path, bool& ours) {
  ours = false;
  struct stat st {};
  if (lstat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode) || st.st_size > (1 << 20)) return {};
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  const std::string s = text.str();
  const auto j = nlohmann::json::parse(s, nullptr, false);
  if (!j.is_object()) return {};
  ours = true;
  std::vector<std::string> out;
  if (j.contains("files") && j["files"].is_array())
    for (const auto& f : j["files"])
      if (f.is_string() && plain_name(f.get<std::string>())) out.push_back(f.get<std::string>());
  return out;
}

void remove_folder(const std::string& dir) {
  if (DIR* d = opendir(dir.c_str())) {
    while (dirent* e = readdir(d)) {
      const std::string name = e->d_name;
      if (name != "." && name != "..") unlink((dir + "/" + name).c_str());
    }
    closedir(d);
  }
  rmdir(dir.c_str());
}

}  // namespace

output_dir::output_dir(std::string dir, std::string manifest, std::string staging, std::vector<std::string> previous)
    : dir_(std::move(dir)), manifest_(std::move(manifest)), staging_(std::move(staging)), previous_(std::move(previous)) {}

output_dir::output_dir(output_dir&& o) noexcept
    : dir_(std::move(o.dir_)), manifest_(std::move(o.manifest_)), staging_(std::move(o.staging_)),
      previous_(std::move(o.previous_)), files_(std::move(o.files_)), manifest_fields_(std::move(o.manifest_fields_)) {
  o.staging_.clear();
}

output_dir::~output_dir() {
  if (!staging_.empty()) remove_folder(staging_);
}

result<output_dir> output_dir::open(const std::string& dir, const std::string& manifest) {
  if (dir.empty()) return failure{"the output folder is empty"};
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  struct stat st {};
  if (stat(dir.c_str(), &st) != 0) return failure{dir + ": cannot make the output folder: " + (ec ? ec.message() : why())};
  if (!S_ISDIR(st.st_mode)) return failure{dir + ": not a folder"};
  std::string staging = dir + "/.dstrans-XXXXXX";
  if (!mkdtemp(staging.data())) return failure{dir + ": cannot write into the output folder: " + why()};
  bool ours = false;
  std::vector<std::string> previous = previous_files(dir + "/" + manifest, ours);
  if (ours) previous.push_back(manifest);
  return output_dir(dir, manifest, staging, previous);
}

result<bool> output_dir::add(const std::string& name, const std::string& bytes) {
  if (!plain_name(name)) return failure{"'" + name + "' is not a plain file name"};
  if (std::find(files_.begin(), files_.end(), name) != files_.end()) return failure{name + ": written twice"};
  const std::string path = staging_ + "/" + name;
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
  if (fd < 0) return failure{dir_ + "/" + name + ": cannot write: " + why()};
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const std::string reason = why();
      ::close(fd);
      return failure{dir_ + "/" + name + ": cannot write: " + reason};
    }
    done += std::size_t(n);
  }
  if (::close(fd) != 0) return failure{dir_ + "/" + name + ": cannot write: " + why()};
  files_.push_back(name);
  return true;
}

result<bool> output_dir::adopt() {
  DIR* d = opendir(staging_.c_str());
  if (!d) return failure{staging_ + ": cannot read: " + why()};
  std::vector<std::string> found;
  while (dirent* e = readdir(d)) {
    const std::string name = e->d_name;
    if (name == "." || name == "..") continue;
    found.push_back(name);
  }
  closedir(d);
  std::sort(found.begin(), found.end());
  for (const std::string& name : found) {
    if (std::find(files_.begin(), files_.end(), name) != files_.end()) continue;
    if (!plain_name(name) || what_is(staging_ + "/" + name) != 1) return failure{staging_ + "/" + name + ": not a plain file"};
    files_.push_back(name);
  }
  return true;
}

result<bool> output_dir::commit() {
  if (staging_.empty()) return failure{dir_ + ": already committed"};
  std::vector<std::string> listed = files_;
  listed.push_back(manifest_);
  nlohmann::ordered_json m = manifest_fields_;
  m["files"] = listed;
  if (auto ok = add(manifest_, m.dump(2) + "\n"); !ok) return ok;
  // Everything is checked before anything moves, so that a refusal leaves DIR as it was.
  for (const std::string& name : files_) {
    const std::string dest = dir_ + "/" + name;
    const int kind = what_is(dest);
    if (kind == 2) return failure{dest + ": exists and is not a plain file (it is not written through or replaced)"};
    if (kind == 1 && std::find(previous_.begin(), previous_.end(), name) == previous_.end())
      return failure{dest + ": exists and is not an output of an earlier dstrans run (" + manifest_ +
                     " does not list it); remove it or choose another --out"};
  }
  for (const std::string& name : files_)
    if (std::rename((staging_ + "/" + name).c_str(), (dir_ + "/" + name).c_str()) != 0)
      return failure{dir_ + "/" + name + ": cannot move into place: " + why()};
  for (const std::string& name : previous_)
    if (std::find(files_.begin(), files_.end(), name) == files_.end() && what_is(dir_ + "/" + name) == 1)
      unlink((dir_ + "/" + name).c_str());
  remove_folder(staging_);
  staging_.clear();
  return true;
}

}  // namespace dstrans
