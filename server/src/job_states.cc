#include "job_states.h"

#include <stdexcept>

namespace dlmfd::server {
namespace {

const JobTransitionRow& Row(JobTransition transition) {
  for (const auto& row : kJobTransitions) {
    if (row.transition == transition) return row;
  }
  throw std::logic_error("job state transition " + std::to_string(static_cast<int>(transition)) +
                         " is not in the table");
}

}  // namespace

bool IsFinished(JobState state) {
  for (const auto& row : kJobStates) {
    if (row.state == state) return row.finished;
  }
  return false;
}

const char* JobStateName(JobState state) {
  for (const auto& row : kJobStates) {
    if (row.state == state) return row.name;
  }
  return "UNKNOWN";
}

bool TransitionAllowed(JobState from, JobState to) {
  for (const auto& row : kJobTransitions) {
    if ((row.from & Of(from)) && (row.to & Of(to))) return true;
  }
  return false;
}

bool TransitionFrom(JobTransition transition, JobState from) {
  return (Row(transition).from & Of(from)) != 0;
}

std::string JobStatesBefore(JobTransition transition) {
  const JobStates from = Row(transition).from;
  std::string list;
  for (const auto& row : kJobStates) {
    if (!(from & Of(row.state))) continue;
    list += (list.empty() ? "(" : ", ") + std::to_string(static_cast<int>(row.state));
  }
  return list + ")";
}

void CheckTransition(JobTransition transition, JobState to) {
  if (!(Row(transition).to & Of(to))) {
    throw std::logic_error(std::string("a job cannot become ") + JobStateName(to) + " when " +
                           Row(transition).when);
  }
}

}  // namespace dlmfd::server
