// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/core/input_file.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <system_error>
#include <thread>
#include <vector>

#include "dform/core/interrupt.h"

namespace dform {
namespace {

namespace fs = std::filesystem;

class InputFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("dform_input_file_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(InputFile, ReadsTheWholeFile) {
  const std::string path = (dir_ / "a.txt").string();
  std::ofstream(path, std::ios::binary) << std::string(100000, 'x') << "end";
  const Result<std::string> text = readInputFile(path);
  ASSERT_TRUE(text.isOk()) << text.status().message();
  EXPECT_EQ(text.value().size(), 100003u);
  EXPECT_EQ(text.value().substr(100000), "end");
}

TEST_F(InputFile, RefusesAFileOverTheLimitWithoutReadingIt) {
  const std::string path = (dir_ / "big.json").string();
  std::ofstream(path, std::ios::binary) << "";
  fs::resize_file(path, kMaxSettingsBytes + 1);  // sparse: nothing is written
  const Result<std::string> text = readInputFile(path, kMaxSettingsBytes);
  EXPECT_EQ(text.status().code(), ErrorCode::InputUnreadable);
  EXPECT_EQ(text.status().message(), path + ": file is too large (1 MiB; the limit is 1 MiB)");
  EXPECT_TRUE(readInputFile(path).isOk()) << "under the default limit";
}

TEST_F(InputFile, StopsAnEndlessStreamAtTheLimit) {
  // A character device reports no size; it is read until the limit, then refused.
  const Result<std::string> text = readInputFile("/dev/zero", kMaxSettingsBytes);
  EXPECT_EQ(text.status().code(), ErrorCode::InputUnreadable);
  EXPECT_NE(text.status().message().find("/dev/zero: file is too large"), std::string::npos)
      << text.status().message();
}

TEST_F(InputFile, MissingFileAndFolderAreUnreadable) {
  const std::string missing = (dir_ / "none.svg").string();
  EXPECT_EQ(readInputFile(missing).status().message(), missing + ": no such file");
  EXPECT_EQ(readInputFile(dir_.string()).status().message(),
            dir_.string() + ": is a folder, not a file");
}

// Where no thread can be started (here: an address-space limit leaving less room than a
// thread's stack), the file is read on the caller's thread.
TEST_F(InputFile, IsReadWithoutAThreadWhereNoneCanBeStarted) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "AddressSanitizer's shadow memory needs more address space than any limit admits";
#endif
  const std::string path = (dir_ / "small.svg").string();
  std::ofstream(path) << "<svg/>";
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    long mappedPages = 0;
    std::ifstream("/proc/self/statm") >> mappedPages;
    // 1 MiB of room: less than any thread stack glibc gives (2 MiB or RLIMIT_STACK's 8 MiB).
    const rlim_t limit = rlim_t(mappedPages) * rlim_t(::sysconf(_SC_PAGESIZE)) + (rlim_t(1) << 20);
    const struct rlimit as = {limit, limit};
    if (::setrlimit(RLIMIT_AS, &as) != 0) ::_exit(2);
    // Threads started and kept until one cannot be (glibc reuses the stacks of threads that
    // ended, which need no new room).
    static std::atomic<bool> release{false};
    std::vector<std::thread> held;
    held.reserve(64);
    try {
      while (held.size() < 64)
        held.emplace_back([] {
          while (!release) std::this_thread::sleep_for(std::chrono::milliseconds(1));
        });
    } catch (const std::system_error&) {
    }
    const bool noThread = held.size() < 64;
    const Result<std::string> text = readInputFile(path);
    ::_exit(!noThread ? 3 : text.isOk() && text.value() == "<svg/>" ? 0 : 1);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status)) << "the child died of signal " << WTERMSIG(status);
  EXPECT_EQ(WEXITSTATUS(status), 0)
      << "1: not read, 2: no limit set, 3: a thread could still start";
}

// A FIFO with no writer blocks its reader's open: a stop ends the read however it arrives.
class BlockedRead : public InputFile {
 protected:
  void SetUp() override {
    InputFile::SetUp();
    fifo_ = (dir_ / "piece.svg").string();
    ASSERT_EQ(::mkfifo(fifo_.c_str(), 0600), 0);
  }
  void TearDown() override {
    interruptFlag() = false;
    // The abandoned read still waits in open(): a writer that comes and goes lets it finish.
    const int fd = ::open(fifo_.c_str(), O_WRONLY | O_NONBLOCK);
    if (fd >= 0) ::close(fd);
    InputFile::TearDown();
  }
  std::string fifo_;
};

TEST_F(BlockedRead, AStopDuringTheWaitEndsIt) {
  std::thread stopper([] {
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    interruptFlag() = true;
  });
  const Result<std::string> text = readInputFile(fifo_);
  stopper.join();
  EXPECT_EQ(text.status().code(), ErrorCode::Interrupted);
  EXPECT_EQ(text.status().message(), fifo_ + ": interrupted while waiting to read it");
}

// A signal that comes before the read blocks (no call left for it to interrupt) still stops it:
// the read would otherwise wait for a writer forever.
TEST_F(BlockedRead, AStopBeforeTheReadEndsIt) {
  interruptFlag() = true;
  const Result<std::string> text = readInputFile(fifo_);
  EXPECT_EQ(text.status().code(), ErrorCode::Interrupted);
}

TEST_F(BlockedRead, AWriterThatComesIsRead) {
  std::thread writer([this] { std::ofstream(fifo_) << "<svg/>"; });
  const Result<std::string> text = readInputFile(fifo_);
  writer.join();
  ASSERT_TRUE(text.isOk()) << text.status().message();
  EXPECT_EQ(text.value(), "<svg/>");
}

}  // namespace
}  // namespace dform
