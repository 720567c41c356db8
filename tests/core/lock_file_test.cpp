// SPDX-License-Identifier: GPL-3.0-or-later
// Lock files and atomic writes beside other people's files: nothing is written through a
// symbolic link, nothing this process did not create is truncated or written.
#include "dform/core/lock_file.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>

#include "dform/core/atomic_file.h"
#include "test_files.h"

namespace dform {
namespace {

namespace fs = std::filesystem;

using test::readText;
using test::writeText;

// A fresh folder for one test, with a "victim" file another user cares about.
struct LockFolder {
  fs::path dir, victim;
  explicit LockFolder(const std::string& name)
      : dir(fs::temp_directory_path() / ("dform_lock_" + name + "_" + std::to_string(::getpid()))),
        victim(dir / "victim.txt") {
    fs::remove_all(dir);
    fs::create_directories(dir);
    writeText(victim, "someone's thesis\n");
  }
  ~LockFolder() { fs::remove_all(dir); }
};

void expectOneLine(const Status& s, const std::string& mention) {
  EXPECT_EQ(s.code(), ErrorCode::OutputFailed) << s.message();
  EXPECT_EQ(s.message().find('\n'), std::string::npos);
  EXPECT_NE(s.message().find(mention), std::string::npos) << s.message();
}

TEST(LockFile, ASymbolicLinkAtTheLockPathIsRefusedAndItsTargetLeftAlone) {
  LockFolder f("link");
  const fs::path lock = f.dir / ".out.dform-lock";
  fs::create_symlink(f.victim, lock);
  for (const bool exclusive : {true, false}) {
    LockFile held;
    const Status s = held.acquire(lock.string(), exclusive, "out");
    expectOneLine(s, "is a symbolic link");
    EXPECT_FALSE(held.held());
  }
  LockFile reading;
  expectOneLine(reading.acquireForReading(lock.string(), "out"), "is a symbolic link");
  EXPECT_EQ(readText(f.victim), "someone's thesis\n");
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(lock)));  // not removed either
  // A link to a folder or to nothing is refused the same way.
  fs::remove(lock);
  fs::create_symlink(f.dir / "nowhere", lock);
  LockFile dangling;
  expectOneLine(dangling.acquire(lock.string(), true, "out"), "is a symbolic link");
  EXPECT_FALSE(fs::exists(f.dir / "nowhere"));
}

TEST(LockFile, AFileItDidNotCreateIsNeverWritten) {
  LockFolder f("foreign");
  const fs::path lock = f.dir / ".out.dform-lock";
  // Another name of the victim (a hard link), as a stale lock file would stand there.
  fs::create_hard_link(f.victim, lock);
  {
    LockFile held;
    ASSERT_TRUE(held.acquire(lock.string(), true, "out").isOk());
    EXPECT_EQ(readText(f.victim), "someone's thesis\n");
    // The lock it holds is a file of its own, naming it.
    EXPECT_EQ(readText(lock), std::to_string(::getpid()));
    EXPECT_FALSE(fs::equivalent(lock, f.victim));
  }
  EXPECT_FALSE(fs::exists(lock));  // removed at release, the victim kept
  EXPECT_EQ(readText(f.victim), "someone's thesis\n");
  // Shared and reading holders only ever read what is there.
  fs::create_hard_link(f.victim, lock);
  {
    LockFile shared, reading;
    ASSERT_TRUE(shared.acquire(lock.string(), false, "out").isOk());
    ASSERT_TRUE(reading.acquireForReading(lock.string(), "out").isOk());
  }
  EXPECT_EQ(readText(f.victim), "someone's thesis\n");
}

TEST(LockFile, SomethingThatIsNotAFileAtTheLockPathIsRefused) {
  LockFolder f("fifo");
  const fs::path lock = f.dir / ".out.dform-lock";
  ASSERT_EQ(::mkfifo(lock.c_str(), 0644), 0);  // a FIFO would block a plain open
  LockFile held;
  expectOneLine(held.acquire(lock.string(), true, "out"), "is not a regular file");
  fs::remove(lock);
  fs::create_directory(lock);
  expectOneLine(held.acquire(lock.string(), true, "out"), "dform-lock");
}

TEST(LockFile, ASecondHolderIsToldWhichProcessHoldsIt) {
  LockFolder f("busy");
  const fs::path lock = f.dir / ".out.dform-lock";
  LockFile first, second, reader;
  ASSERT_TRUE(first.acquire(lock.string(), true, "out").isOk());
  expectOneLine(second.acquire(lock.string(), true, "out"),
                "(process " + std::to_string(::getpid()) + ")");
  expectOneLine(reader.acquireForReading(lock.string(), "out"), "another dform run");
  first.release();
  EXPECT_FALSE(fs::exists(lock));
  // A reader keeps a writer off, and readers share.
  LockFile r1, r2, writer;
  ASSERT_TRUE(r1.acquireForReading(lock.string(), "out").isOk());
  ASSERT_TRUE(r2.acquireForReading(lock.string(), "out").isOk());
  expectOneLine(writer.acquire(lock.string(), true, "out"), "another dform run");
}

TEST(LockFile, ARunInsideAFolderAnotherRunReplacesIsRefused) {
  LockFolder f("enclosing");
  fs::create_directories(f.dir / "W" / "deeper");
  EXPECT_TRUE(checkNoEnclosingRun((f.dir / "W" / "mine").string(), "W/mine").isOk());
  LockFile sweep;
  ASSERT_TRUE(sweep.acquire((f.dir / ".W.dform-lock").string(), true, "W").isOk());
  expectOneLine(checkNoEnclosingRun((f.dir / "W" / "mine").string(), "W/mine"),
                "is being replaced by another dform run (process " + std::to_string(::getpid()));
  expectOneLine(checkNoEnclosingRun((f.dir / "W" / "deeper" / "x").string(), "W/deeper/x"),
                "W/deeper/x: ");
  // Beside it, or W itself (its own lock decides), is no concern of this check.
  EXPECT_TRUE(checkNoEnclosingRun((f.dir / "V" / "mine").string(), "V/mine").isOk());
  EXPECT_TRUE(checkNoEnclosingRun((f.dir / "W").string(), "W").isOk());
  sweep.release();
  EXPECT_TRUE(checkNoEnclosingRun((f.dir / "W" / "mine").string(), "W/mine").isOk());
}

TEST(AtomicFile, ALinkAtTheTemporaryPathIsRefusedAndItsTargetLeftAlone) {
  LockFolder f("atomic");
  const fs::path out = f.dir / "batch.json";
  const fs::path temporary = f.dir / ("batch.json.tmp." + std::to_string(::getpid()));
  fs::create_symlink(f.victim, temporary);
  const Status s = writeFileAtomically(out.string(), "{}\n");
  expectOneLine(s, temporary.string() + ": is in the way");
  EXPECT_EQ(readText(f.victim), "someone's thesis\n");
  EXPECT_FALSE(fs::exists(out));
  // A link at the target itself is replaced by the new file, not written through.
  fs::remove(temporary);
  fs::create_symlink(f.victim, out);
  ASSERT_TRUE(writeFileAtomically(out.string(), "{}\n").isOk());
  EXPECT_FALSE(fs::is_symlink(fs::symlink_status(out)));
  EXPECT_EQ(readText(out), "{}\n");
  EXPECT_EQ(readText(f.victim), "someone's thesis\n");
}

}  // namespace
}  // namespace dform
