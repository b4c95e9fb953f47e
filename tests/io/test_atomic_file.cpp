// Atomic outputs (io/atomic_file.hpp): a file is complete or absent, and a write that fails is an error naming the
// file. The failure is made real with the file size limit of the process (RLIMIT_FSIZE, as a full disk would).

#include <doctest/doctest.h>

#include <sys/resource.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "../file_contents.hpp"
#include "../integrate/fixtures.hpp"
#include "blockdem/io/atomic_file.hpp"
#include "blockdem/io/vtk.hpp"

using namespace blockdem;

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_atomic_file {

namespace {

/// Files larger than `bytes` cannot be written while it lives (writes fail with EFBIG instead of raising SIGXFSZ).
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    getrlimit(RLIMIT_FSIZE, &saved_);
    previous_handler_ = std::signal(SIGXFSZ, SIG_IGN);
    rlimit limit = saved_;
    limit.rlim_cur = bytes;
    setrlimit(RLIMIT_FSIZE, &limit);
  }
  ~FileSizeLimit() {
    setrlimit(RLIMIT_FSIZE, &saved_);
    std::signal(SIGXFSZ, previous_handler_);
  }
  FileSizeLimit(const FileSizeLimit&) = delete;
  FileSizeLimit& operator=(const FileSizeLimit&) = delete;

 private:
  rlimit saved_{};
  void (*previous_handler_)(int) = nullptr;
};

std::string error_of(auto&& write) {
  try {
    write();
  } catch (const InvalidArgument& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST_CASE("atomic file: the file appears whole, under its name, only when its writer is done") {
  const auto dir = std::filesystem::temp_directory_path() / "blockdem_atomic_file";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "table.csv").string();
  io::write_atomically(path, [&](std::ostream& out) {
    out << "a,b\n";
    CHECK_FALSE(std::filesystem::exists(path));  // still under its temporary name
    CHECK(std::filesystem::exists(io::partial_path(path)));
    out << "1,2\n";
  });
  CHECK(test::file_contents(path) == "a,b\n1,2\n");
  CHECK_FALSE(std::filesystem::exists(io::partial_path(path)));
  // A writer that throws leaves the previous file as it was and no temporary file.
  CHECK_THROWS_AS(io::write_atomically(path, [&](std::ostream& out) {
                    out << "half";
                    throw InvalidArgument("stopped");
                  }),
                  InvalidArgument);
  CHECK(test::file_contents(path) == "a,b\n1,2\n");
  CHECK_FALSE(std::filesystem::exists(io::partial_path(path)));
  std::filesystem::remove_all(dir);
}

TEST_CASE("atomic file: a write that fails (file too large, as on a full disk) names the file and keeps the old one") {
  const auto dir = std::filesystem::temp_directory_path() / "blockdem_atomic_full";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "big.csv").string();
  io::write_atomically(path, [&](std::ostream& out) { out << "previous\n"; });
  const std::string big(200000, 'x');
  std::string message;
  {
    const FileSizeLimit limit(65536);
    message = error_of([&] { io::write_atomically(path, [&](std::ostream& out) { out << big; }); });
  }
  CHECK(message.find("cannot write '" + path + "'") != std::string::npos);
  CHECK(message.find("File too large") != std::string::npos);
  CHECK(test::file_contents(path) == "previous\n");
  CHECK_FALSE(std::filesystem::exists(io::partial_path(path)));

  // The same through a VTK writer: the model is large enough to pass the limit.
  auto s = test::block_on_base(1, 1, 1);
  for (int i = 0; i < 400; ++i) {
    std::string name = "b";  // (not "b" + std::to_string: GCC 12 warns wrongly of an overlap)
    name += std::to_string(i);
    s.model.add_block(geometry::make_box(Vec3(0, 0, 5.0 + i), Vec3(0.1, 0.1, 5.1 + i)), 2000.0, name, 1);
  }
  const std::string vtu = (dir / "blocks.vtu").string();
  {
    const FileSizeLimit limit(16384);
    message = error_of([&] { io::write_blocks_vtu(vtu, s.model); });
  }
  CHECK(message.find("cannot write '" + vtu + "'") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(vtu));
  CHECK_FALSE(std::filesystem::exists(io::partial_path(vtu)));
  io::write_blocks_vtu(vtu, s.model);  // without the limit it is written whole
  CHECK(test::file_contents(vtu).ends_with("</VTKFile>\n"));
  std::filesystem::remove_all(dir);
}

TEST_CASE("atomic file: a folder that does not exist is named") {
  const std::string message = error_of([] { io::write_atomically("/nonexistent-dir/a.csv", [](std::ostream& out) { out << 1; }); });
  CHECK(message.find("cannot open '/nonexistent-dir/a.csv' for writing") != std::string::npos);
  CHECK(message.find("No such file or directory") != std::string::npos);
}

}  // namespace test_atomic_file
