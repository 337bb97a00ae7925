// The output-folder lock (io/folder_lock.hpp) and the output folder's refusal to write over
// files it did not write: a live holder is refused and named, a stale lock of this host is
// refused unless taken over (then reported), a lock of another host is never taken over,
// and the lock file goes when its holder is done.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/file.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "../cli_helpers.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "io/folder_lock.hpp"
#include "io/output.hpp"

namespace bkq {
namespace {

namespace fs = std::filesystem;

std::string this_host() {
  char buf[256] = {};
  ::gethostname(buf, sizeof buf - 1);
  return buf;
}

// The message of the bkq::Error `f` throws ("" when it throws none).
template <class F>
std::string error_of(F f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

std::string lock_text(const std::string& host, long pid) {
  return "bkquake folder lock\nhost " + host + "\npid " + std::to_string(pid) +
         "\ncommand run\nsince 2026-01-01T00:00:00Z\n";
}

TEST(FolderLock, HeldWhileAliveAndRemovedAfter) {
  test::TempDir tmp;
  const std::string dir = tmp.path().string();
  {
    FolderLock lock(dir, "run", StaleLock::Refuse);
    const auto holder = read_folder_lock(dir);
    ASSERT_TRUE(holder.has_value());
    EXPECT_EQ(holder->pid, ::getpid());
    EXPECT_EQ(holder->host, this_host());
    EXPECT_EQ(holder->command, "run");
    // A second taker, even with TakeOver, finds it held (flocks conflict within a process
    // too) and names the holder.
    const std::string e = error_of([&] { FolderLock(dir, "merge", StaleLock::TakeOver); });
    EXPECT_NE(e.find("is in use by bkquake run (pid " + std::to_string(::getpid())),
              std::string::npos)
        << e;
  }
  EXPECT_FALSE(fs::exists(tmp.file(FolderLock::kFileName)));
  EXPECT_TRUE(fs::is_empty(dir)) << "no temporary file is left behind";
}

// A process killed between creating its lock temporary and unlinking it leaves the
// temporary; the next process to take the lock removes it, but not the temporary of a live
// process, which holds its flock (it once stood among a resumed sweep's files).
TEST(FolderLock, TakingTheLockRemovesTheTemporaryOfAKilledAttempt) {
  test::TempDir tmp;
  const std::string dir = tmp.path().string();
  const std::string dead = dir + "/" + FolderLock::kTemporaryPrefix + "Dead01";
  const std::string live = dir + "/" + FolderLock::kTemporaryPrefix + "Live01";
  std::ofstream(dead) << "bkquake folder lock\n";
  std::ofstream(live) << "bkquake folder lock\n";
  const int held = ::open(live.c_str(), O_RDWR | O_CLOEXEC);
  ASSERT_GE(held, 0);
  ASSERT_EQ(::flock(held, LOCK_EX | LOCK_NB), 0);
  {
    FolderLock lock(dir, "run", StaleLock::Refuse);
    EXPECT_FALSE(fs::exists(dead));
    EXPECT_TRUE(fs::exists(live));
  }
  ::close(held);
}

TEST(FolderLock, StaleLockOfThisHostIsRefusedOrTakenOver) {
  test::TempDir tmp;
  const std::string dir = tmp.path().string();
  // Nobody flocks a file written by hand: its holder is gone.
  tmp.write(FolderLock::kFileName, lock_text(this_host(), 999999));
  const std::string e = error_of([&] { FolderLock(dir, "run", StaleLock::Refuse); });
  EXPECT_NE(e.find("stale lock of bkquake run (pid 999999 on host " + this_host()),
            std::string::npos)
      << e;
  EXPECT_NE(e.find("--resume"), std::string::npos) << e;
  EXPECT_NE(e.find("--force"), std::string::npos) << e;
  EXPECT_TRUE(fs::exists(tmp.file(FolderLock::kFileName))) << "a refusal leaves the lock";
  {
    FolderLock lock(dir, "run", StaleLock::TakeOver);
    EXPECT_EQ(read_folder_lock(dir)->pid, ::getpid());
  }
  EXPECT_FALSE(fs::exists(tmp.file(FolderLock::kFileName)));
}

TEST(FolderLock, LockOfAnotherHostIsNeverTakenOver) {
  test::TempDir tmp;
  const std::string dir = tmp.path().string();
  const std::string text = lock_text("elsewhere.invalid", 1234);
  tmp.write(FolderLock::kFileName, text);
  for (const StaleLock s : {StaleLock::Refuse, StaleLock::TakeOver}) {
    const std::string e = error_of([&] { FolderLock(dir, "run", s); });
    EXPECT_NE(e.find("host elsewhere.invalid"), std::string::npos) << e;
    EXPECT_NE(e.find("never taken over"), std::string::npos) << e;
  }
  EXPECT_EQ(test::read_file(tmp.file(FolderLock::kFileName)), text);
}

TEST(FolderLock, GarbledLockPrintsNoRawBytes) {
  test::TempDir tmp;
  tmp.write(FolderLock::kFileName, std::string("host \x01\x9b[2J\xff", 10) + "\npid x\n");
  const std::string e =
      error_of([&] { FolderLock(tmp.path().string(), "run", StaleLock::Refuse); });
  EXPECT_NE(e.find("unknown process"), std::string::npos) << e;
  for (const char c : e) EXPECT_TRUE(c >= 0x20 && c < 0x7f) << e;
}

TEST(OutputFolder, RefusesAStrayFileWithoutForce) {
  test::TempDir tmp;
  const std::string dir = tmp.path().string();
  const std::string stray = tmp.write("catalog.csv", "not ours\n");
  const std::string e = error_of([&] { OutputFolder(dir, false, false); });
  EXPECT_NE(e.find("already holds files bkquake did not write in this run ('catalog.csv')"),
            std::string::npos)
      << e;
  EXPECT_NE(e.find("--force"), std::string::npos) << e;
  EXPECT_EQ(test::read_file(stray), "not ours\n");
  EXPECT_NO_THROW(OutputFolder(dir, true, false));
  // Hidden files and folders do not count.
  test::TempDir other;
  other.write(".hidden", "");
  fs::create_directory(other.file("sub"));
  EXPECT_NO_THROW(OutputFolder(other.path().string(), false, false));
}

TEST(OutputFolder, ResumeNeedsAnExistingFolder) {
  test::TempDir tmp;
  const std::string dir = tmp.file("missing");
  const std::string e = error_of([&] { OutputFolder(dir, false, true); });
  EXPECT_NE(e.find("'" + dir + "' does not exist"), std::string::npos) << e;
  EXPECT_FALSE(fs::exists(dir)) << "a refused resume creates nothing";
}

TEST(QuotePrintable, EscapesEverythingButPrintableAscii) {
  EXPECT_EQ(quote_printable("abc"), "'abc'");
  EXPECT_EQ(quote_printable(std::string("a\x00\x1b\xff\\", 5)), "'a\\x00\\x1b\\xff\\'");
  EXPECT_EQ(quote_printable("abcdef", 3), "'abc...'");
}

}  // namespace
}  // namespace bkq
