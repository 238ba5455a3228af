#!/usr/bin/env bash
# The rule for commit messages (CONTRIBUTING.md): a subject of at most 72 characters, then a blank
# line and the body, where the numbers go. One function, used by the commit-msg hook on a message
# file and by scripts/test.sh on the commits made since the rule was enforced.
#
#   scripts/commit_message.sh FILE         checks one message (the hook: scripts/git-hooks/commit-msg)
#   scripts/commit_message.sh --since REV  checks every commit after REV on HEAD's history
set -euo pipefail

max_subject=72

# Prints what is wrong with the message on stdin (nothing when it follows the rule).
message_faults() {
  # Comment lines are what git strips before committing.
  local text subject second
  text=$(grep -v '^#' || true)
  subject=$(printf '%s\n' "$text" | sed -n 1p)
  second=$(printf '%s\n' "$text" | sed -n 2p)
  if [ -z "${subject//[[:space:]]/}" ]; then
    echo "the subject (first line) is empty"
  elif [ "${#subject}" -gt "$max_subject" ]; then
    echo "the subject has ${#subject} characters; at most $max_subject (move the detail and the numbers to the body)"
  fi
  if [ -n "$second" ]; then
    echo "the second line must be blank (the body starts on the third)"
  fi
}

if [ "${1:-}" = "--since" ]; then
  status=0
  for commit in $(git rev-list --no-merges "$2..HEAD"); do
    faults=$(git log -1 --format=%B "$commit" | message_faults)
    if [ -n "$faults" ]; then
      echo "commit $(git log -1 --format='%h %s' "$commit"):" >&2
      printf '  %s\n' "$faults" >&2
      status=1
    fi
  done
  exit "$status"
fi

if [ $# -ne 1 ] || [ ! -f "$1" ]; then
  echo "usage: scripts/commit_message.sh MESSAGE_FILE | --since REV" >&2
  exit 2
fi
faults=$(message_faults < "$1")
if [ -n "$faults" ]; then
  echo "commit message refused (CONTRIBUTING.md, \"Commits\"):" >&2
  printf '  %s\n' "$faults" >&2
  exit 1
fi
