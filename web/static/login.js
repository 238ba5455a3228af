"use strict";
// Fixed messages only: nothing of the URL is shown back.
const reasons = {
  rejected: "The daemon did not accept that token.",
  empty: "Give a token.",
  unreachable: "The daemon cannot be reached; try again in a moment.",
};
const reason = new URLSearchParams(window.location.search).get("error");
if (reason && reasons[reason]) {
  const box = document.getElementById("notice");
  box.textContent = reasons[reason];
  box.className = "notice error";
}
