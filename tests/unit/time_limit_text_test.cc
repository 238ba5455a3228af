// `dlmfd submit/study --time`: the durations a Slurm user writes (units and sbatch's forms) and the
// texts refused with a message saying what is expected (client/src/time_limit_text.h).
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "time_limit_text.h"

namespace dlmfd::cli {
namespace {

TEST(TimeLimitText, UnitsAndSumsOfThem) {
  EXPECT_EQ(ParseTimeLimit("90m"), 5400);
  EXPECT_EQ(ParseTimeLimit("2h"), 7200);
  EXPECT_EQ(ParseTimeLimit("45s"), 45);
  EXPECT_EQ(ParseTimeLimit("1d"), 86400);
  EXPECT_EQ(ParseTimeLimit("1h30m"), 5400);
  EXPECT_EQ(ParseTimeLimit("1d12h"), 129600);
  EXPECT_EQ(ParseTimeLimit("2h0m30s"), 7230);
}

TEST(TimeLimitText, SbatchForms) {
  EXPECT_EQ(ParseTimeLimit("90"), 5400);            // minutes
  EXPECT_EQ(ParseTimeLimit("90:30"), 5430);         // minutes:seconds
  EXPECT_EQ(ParseTimeLimit("1:30:00"), 5400);       // hours:minutes:seconds
  EXPECT_EQ(ParseTimeLimit("2-12"), 216000);        // days-hours
  EXPECT_EQ(ParseTimeLimit("2-12:30"), 217800);     // days-hours:minutes
  EXPECT_EQ(ParseTimeLimit("2-12:30:05"), 217805);  // days-hours:minutes:seconds
}

// The message of a refused text, or empty when it was accepted.
std::string Refusal(const std::string& text) {
  try {
    ParseTimeLimit(text);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return {};
}

TEST(TimeLimitText, RefusesWhatIsNotAPositiveDuration) {
  for (const char* text : {"", "0", "0m", "0:00:00", "-5", "5x", "m", "30m1h", "1h1h", "1h30",
                           "1:2:3:4", "1.5h", "abc", "1-", ":30", "99999999999"}) {
    const std::string message = Refusal(text);
    EXPECT_FALSE(message.empty()) << "accepted \"" << text << "\"";
    EXPECT_EQ(message.rfind(std::string("--time ") + text + ": ", 0), 0u) << message;
    EXPECT_NE(message.find("expected a positive duration"), std::string::npos) << message;
  }
  EXPECT_NE(Refusal("0").find("give no --time for the daemon's limit"), std::string::npos);
}

}  // namespace
}  // namespace dlmfd::cli
