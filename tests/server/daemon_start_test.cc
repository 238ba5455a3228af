// The real dlmfdd at start: what it refuses (a port in use or out of range, an empty tokens file, a
// solver that is not there), what it warns about (a tokens file others can read) and what its
// health service answers for.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "support/daemon_process.h"

namespace dlmfd::testing {
namespace {
namespace fs = std::filesystem;

constexpr char kStartAliceToken[] = "alice-token-0123456789";

// Expects the daemon to refuse to start with `exit_status` and `in_log` in what it printed.
void ExpectRefused(DaemonProcess& daemon, int exit_status, const std::string& in_log) {
  ASSERT_FALSE(daemon.Start()) << "it started; log:\n" << daemon.Log();
  EXPECT_EQ(daemon.start_exit_status(), exit_status) << daemon.Log();
  EXPECT_NE(daemon.Log().find(in_log), std::string::npos) << daemon.Log() << "\nlacks " << in_log;
}

TEST(DaemonStart, ASecondDaemonOnTheSamePortExitsAndTheFirstKeepsServing) {
  TempDir dir;
  DaemonProcess first(dir.path() + "/first");
  ASSERT_TRUE(first.Start()) << first.Log();
  DaemonProcess second(dir.path() + "/second", {}, first.address());
  ExpectRefused(second, 1, "cannot listen on " + first.address());
  EXPECT_FALSE(fs::exists(dir.path() + "/second.port"));
  EXPECT_TRUE(first.Healthy());
}

// Issue 38: a second daemon could bind [::1] on a port whose 127.0.0.1 a first one served, and
// clients of localhost:PORT then sent their token to either.
TEST(DaemonStart, ASecondDaemonCannotTakeTheOtherLoopbackAddressOfAPortInUse) {
  TempDir dir;
  DaemonProcess first(dir.path() + "/first");
  ASSERT_TRUE(first.Start()) << first.Log();
  const std::string port = std::to_string(first.port());
  int tried = 0;
  for (const std::string& listen : {"[::1]:" + port, "localhost:" + port}) {
    DaemonProcess second(dir.path() + "/second" + std::to_string(++tried), {}, listen);
    ExpectRefused(second, 1, "port " + port + " is in use on 127.0.0.1");
  }
  EXPECT_TRUE(first.Healthy());
  // And the other way round: a daemon on [::1] keeps 127.0.0.1 of its port too.
  const std::string v6_port = std::to_string(first.port() + 1);
  DaemonProcess on_v6(dir.path() + "/v6", {}, "[::1]:" + v6_port);
  if (!on_v6.Start()) GTEST_SKIP() << "no [::1]:" << v6_port << " here: " << on_v6.Log();
  DaemonProcess on_v4(dir.path() + "/v4", {}, "127.0.0.1:" + v6_port);
  ExpectRefused(on_v4, 1, "port " + v6_port + " is in use on 127.0.0.1");
}

TEST(DaemonStart, PortsOutsideTheirRangeAreRefusedNamingListen) {
  TempDir dir;
  int tried = 0;
  for (const std::string listen : {"127.0.0.1:99999", "127.0.0.1:-1", "127.0.0.1:", "127.0.0.1",
                                   "[::1]:65536", "localhost:80x"}) {
    // A data directory (and so a log) of its own per address.
    DaemonProcess daemon(dir.path() + "/data" + std::to_string(++tried), {}, listen);
    ExpectRefused(daemon, 2, "listen = \"" + listen + "\"");
    EXPECT_NE(daemon.Log().find("0 to 65535"), std::string::npos) << daemon.Log();
  }
}

TEST(DaemonStart, AnEmptyTokensFileIsAnError) {
  TempDir dir;
  const std::string tokens = dir.path() + "/tokens";
  std::ofstream(tokens) << "# no tokens yet\n\n";
  chmod(tokens.c_str(), 0600);
  DaemonProcess daemon(dir.path() + "/data", {"--tokens-file", tokens});
  ExpectRefused(daemon, 2, "tokens_file = \"" + tokens + "\" has no tokens");
}

TEST(DaemonStart, ATokensFileOthersCanReadGetsAWarning) {
  TempDir dir;
  const std::string tokens = dir.path() + "/tokens";
  std::ofstream(tokens) << kStartAliceToken << " alice\n";
  chmod(tokens.c_str(), 0644);
  {
    DaemonProcess daemon(dir.path() + "/data", {"--tokens-file", tokens});
    ASSERT_TRUE(daemon.Start()) << daemon.Log();
    EXPECT_NE(daemon.Log().find("warning tokens_file = \"" + tokens + "\" can be read by"),
              std::string::npos)
        << daemon.Log();
  }
  chmod(tokens.c_str(), 0600);
  DaemonProcess daemon(dir.path() + "/private", {"--tokens-file", tokens});
  ASSERT_TRUE(daemon.Start()) << daemon.Log();
  EXPECT_EQ(daemon.Log().find("can be read by"), std::string::npos) << daemon.Log();
}

TEST(DaemonStart, ASolverThatIsNotThereIsRefusedNamingSolver) {
  TempDir dir;
  DaemonProcess missing(dir.path() + "/data", {"--solver", dir.path() + "/nonexistent"});
  ExpectRefused(missing, 2, "solver = \"" + dir.path() + "/nonexistent\" (--solver");
  DaemonProcess directory(dir.path() + "/data", {"--solver", dir.path()});
  ExpectRefused(directory, 2, "is not an executable file");
}

TEST(DaemonStart, HealthAnswersServingForTheServerAndForTheJobsService) {
  TempDir dir;
  DaemonProcess daemon(dir.path() + "/data");
  ASSERT_TRUE(daemon.Start()) << daemon.Log();
  EXPECT_TRUE(daemon.Healthy());
  EXPECT_TRUE(daemon.Healthy("dlmfd.v1.Jobs"));
  EXPECT_FALSE(daemon.Healthy("dlmfd.v1.NoSuchService"));
}

}  // namespace
}  // namespace dlmfd::testing
