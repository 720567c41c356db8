// SPDX-License-Identifier: GPL-3.0-or-later
// A result folder replaced beside other people: its staging and old paths never followed, and
// nothing that appears in it while a run works is ever deleted.
#include "dform/core/result_folder.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "test_files.h"

namespace dform {
namespace {

namespace fs = std::filesystem;

using test::readText;
using test::writeText;

struct Folder {
  fs::path dir, out, victim;
  explicit Folder(const std::string& name)
      : dir(fs::temp_directory_path() /
            ("dform_result_" + name + "_" + std::to_string(::getpid()))),
        out(dir / "out"),
        victim(dir / "victim.txt") {
    fs::remove_all(dir);
    fs::create_directories(out);
    writeText(out / "report.json", "old\n");
    writeText(victim, "someone's thesis\n");
  }
  ~Folder() { fs::remove_all(dir); }
  fs::path beside(const std::string& what) const {
    return dir / (".out.dform-" + what + "." + std::to_string(::getpid()));
  }
};

const std::set<std::string> kResult = {"report.json", "report.html"};

TEST(ResultFolder, ALinkAtItsStagingOrOldPathIsRefusedAndItsTargetLeftAlone) {
  for (const char* what : {"new", "old"}) {
    Folder f(what);
    fs::create_symlink(f.victim, f.beside(what));
    ResultFolder folder;
    const Status s = folder.begin(f.out.string(), kResult);
    EXPECT_EQ(s.code(), ErrorCode::OutputFailed) << what;
    EXPECT_NE(s.message().find(f.beside(what).string() + " is in the way"), std::string::npos)
        << s.message();
    EXPECT_EQ(s.message().find('\n'), std::string::npos);
    EXPECT_EQ(readText(f.victim), "someone's thesis\n");
    EXPECT_TRUE(fs::is_symlink(fs::symlink_status(f.beside(what))));
    EXPECT_EQ(readText(f.out / "report.json"), "old\n");
  }
}

TEST(ResultFolder, ALeftoverOfThisUsersKilledRunIsRemoved) {
  Folder f("leftover");
  fs::create_directory(f.dir / ".out.dform-new.99999999");
  writeText(f.dir / ".out.dform-new.99999999" / "report.json", "half\n");
  ResultFolder folder;
  ASSERT_TRUE(folder.begin(f.out.string(), kResult).isOk());
  EXPECT_FALSE(fs::exists(f.dir / ".out.dform-new.99999999"));
}

TEST(ResultFolder, WhatAppearsWhileTheRunWritesIsKeptInTheNewResult) {
  Folder f("appeared");
  writeText(f.out / "report.html", "old page\n");
  MessageSink sink;
  {
    ResultFolder folder;
    ASSERT_TRUE(folder.begin(f.out.string(), kResult).isOk());
    writeText(fs::path(folder.staging()) / "report.json", "new\n");
    // Meanwhile a user saves notes into the folder and a run writes a folder inside it.
    writeText(f.out / "notes.txt", "mine\n");
    fs::create_directory(f.out / "mine");
    writeText(f.out / "mine" / "report.json", "nested\n");
    ASSERT_TRUE(folder.commit(&sink).isOk());
  }
  EXPECT_EQ(readText(f.out / "report.json"), "new\n");
  EXPECT_FALSE(fs::exists(f.out / "report.html"));  // of the old result: goes with the swap
  EXPECT_EQ(readText(f.out / "notes.txt"), "mine\n");
  EXPECT_EQ(readText(f.out / "mine" / "report.json"), "nested\n");
  ASSERT_EQ(sink.messages().size(), 2u);
  for (const Message& m : sink.messages()) {
    EXPECT_EQ(m.level, Level::Warning);
    EXPECT_NE(m.text.find("appeared while dform was writing"), std::string::npos) << m.text;
  }
  for (const fs::directory_entry& entry : fs::directory_iterator(f.dir))  // nothing left beside
    EXPECT_EQ(entry.path().filename().string().find(".out.dform-"), std::string::npos)
        << entry.path();
}

TEST(ResultFolder, WhatAppearedUnderANameTheNewResultHasIsKeptAside) {
  Folder f("clash");
  ResultFolder folder;
  ASSERT_TRUE(folder.begin(f.out.string(), kResult).isOk());
  writeText(fs::path(folder.staging()) / "report.json", "new\n");
  writeText(fs::path(folder.staging()) / "report.html", "new page\n");
  writeText(f.out / "report.html", "the user's page\n");  // appeared after begin
  MessageSink sink;
  ASSERT_TRUE(folder.commit(&sink).isOk());
  EXPECT_EQ(readText(f.out / "report.html"), "new page\n");
  const fs::path kept = f.beside("kept");
  EXPECT_EQ(readText(kept / "report.html"), "the user's page\n");
  EXPECT_FALSE(fs::exists(kept / "report.json"));  // the old result's own file went
  ASSERT_EQ(sink.messages().size(), 1u);
  EXPECT_NE(sink.messages()[0].text.find(kept.string()), std::string::npos);
}

TEST(ResultFolder, AFileReplacedUnderItsNameSinceBeginIsNotTheOneBeginFound) {
  Folder f("replaced");
  ResultFolder folder;
  ASSERT_TRUE(folder.begin(f.out.string(), kResult).isOk());
  writeText(fs::path(folder.staging()) / "report.html", "new page\n");
  // report.json swapped for another file of the same name: the user's, not the old result's.
  fs::remove(f.out / "report.json");
  writeText(f.out / "report.json", "the user's\n");
  MessageSink sink;
  ASSERT_TRUE(folder.commit(&sink).isOk());
  EXPECT_EQ(readText(f.out / "report.json"), "the user's\n");  // moved in: the name was free
  EXPECT_EQ(sink.messages().size(), 1u);
}

TEST(ResultFolder, ReadingHoldsOffAWriterWithoutStagingAnything) {
  Folder f("reading");
  ResultFolder reader;
  ASSERT_TRUE(reader.read(f.out.string()).isOk());
  ResultFolder writer;
  const Status s = writer.begin(f.out.string(), kResult);
  EXPECT_EQ(s.code(), ErrorCode::OutputFailed);
  EXPECT_NE(s.message().find("another dform run"), std::string::npos);
  int entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(f.dir)) ++entries;
  EXPECT_EQ(entries, 3);  // out, victim.txt and the lock
  ResultFolder second;
  EXPECT_TRUE(second.read(f.out.string()).isOk());
}

}  // namespace
}  // namespace dform
