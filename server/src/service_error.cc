#include "service_error.h"

#include <spdlog/spdlog.h>

#include <new>

#include "dlmfd/core/errors.h"
#include "job_store.h"

namespace dlmfd::server {

grpc::Status ToStatus(std::exception_ptr error) {
  try {
    std::rethrow_exception(error);
  } catch (const ServiceError& e) {
    return {e.code(), e.what()};
  } catch (const dlmfd::InvalidParameter& e) {
    return {grpc::StatusCode::INVALID_ARGUMENT, e.what()};
  } catch (const StoreError& e) {
    spdlog::error("store: {}", e.what());
    return {grpc::StatusCode::INTERNAL, std::string("job store: ") + e.what()};
  } catch (const std::bad_alloc&) {
    return {grpc::StatusCode::RESOURCE_EXHAUSTED, "out of memory"};
  } catch (const std::exception& e) {
    spdlog::error("internal error: {}", e.what());
    return {grpc::StatusCode::INTERNAL, std::string("internal error: ") + e.what()};
  } catch (...) {
    spdlog::error("internal error: unknown exception");
    return {grpc::StatusCode::INTERNAL, "internal error"};
  }
}

}  // namespace dlmfd::server
