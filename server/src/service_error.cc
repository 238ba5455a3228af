#include "service_error.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <new>

#include "dlmfd/core/errors.h"
#include "job_store.h"

namespace dlmfd::server {

namespace {

bool IsUtf8Continuation(char c) { return (static_cast<unsigned char>(c) & 0xC0) == 0x80; }

// The largest n <= limit such that text[0, n) ends on a UTF-8 character boundary.
size_t HeadBoundary(std::string_view text, size_t limit) {
  size_t n = std::min(limit, text.size());
  while (n > 0 && n < text.size() && IsUtf8Continuation(text[n])) --n;
  return n;
}

// Control bytes as \xNN, except the line breaks and tabs a message may hold for layout.
std::string EscapeControl(std::string_view text, bool keep_layout) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if ((byte < 0x20 || byte == 0x7F) && !(keep_layout && (c == '\n' || c == '\t'))) {
      static const char kHex[] = "0123456789abcdef";
      out += "\\x";
      out += kHex[byte >> 4];
      out += kHex[byte & 15];
    } else {
      out += c;
    }
  }
  return out;
}

}  // namespace

void RequireNoNul(std::string_view field, std::string_view text) {
  const size_t at = text.find('\0');
  if (at == std::string_view::npos) return;
  throw ServiceError(grpc::StatusCode::INVALID_ARGUMENT,
                     std::string(field) + ": \"" + CutForMessage(text) +
                         "\" contains a NUL byte (at byte " + std::to_string(at) +
                         "): expected text without NUL bytes");
}

std::string CutForMessage(std::string_view value, size_t keep) {
  if (value.size() <= keep) return EscapeControl(value, false);
  return EscapeControl(value.substr(0, HeadBoundary(value, keep)), false) + "... (" +
         std::to_string(value.size()) + " bytes)";
}

std::string BoundMessage(std::string_view message) {
  const std::string text = EscapeControl(message, true);
  if (text.size() <= kMessageBytes) return text;
  const std::string_view view(text);
  const size_t head = HeadBoundary(view, kMessageBytes / 2);
  size_t tail = text.size() - kMessageBytes / 4;
  while (tail < text.size() && IsUtf8Continuation(text[tail])) ++tail;
  return std::string(view.substr(0, head)) + " ... (" + std::to_string(tail - head) +
         " bytes cut) ... " + std::string(view.substr(tail));
}

grpc::Status ToStatus(std::exception_ptr error) {
  try {
    std::rethrow_exception(error);
  } catch (const ServiceError& e) {
    return {e.code(), BoundMessage(e.what())};
  } catch (const dlmfd::InvalidParameter& e) {
    return {grpc::StatusCode::INVALID_ARGUMENT, BoundMessage(e.what())};
  } catch (const StoreError& e) {
    spdlog::error("store: {}", e.what());
    return {grpc::StatusCode::INTERNAL, BoundMessage(std::string("job store: ") + e.what())};
  } catch (const std::bad_alloc&) {
    return {grpc::StatusCode::RESOURCE_EXHAUSTED, "out of memory"};
  } catch (const std::exception& e) {
    spdlog::error("internal error: {}", e.what());
    return {grpc::StatusCode::INTERNAL, BoundMessage(std::string("internal error: ") + e.what())};
  } catch (...) {
    spdlog::error("internal error: unknown exception");
    return {grpc::StatusCode::INTERNAL, "internal error"};
  }
}

}  // namespace dlmfd::server
