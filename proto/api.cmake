# The job API (dlmfd.v1.Jobs): protobuf + gRPC code from jobs.proto, linked with the event stream
# messages it imports. Included by proto/CMakeLists.txt when the service is built.
set(API_PROTO dlmfd/v1/jobs.proto)
set(API_PB_CC ${PROTO_OUT}/dlmfd/v1/jobs.pb.cc)
set(API_PB_H ${PROTO_OUT}/dlmfd/v1/jobs.pb.h)
set(API_GRPC_CC ${PROTO_OUT}/dlmfd/v1/jobs.grpc.pb.cc)
set(API_GRPC_H ${PROTO_OUT}/dlmfd/v1/jobs.grpc.pb.h)

get_target_property(DLMFD_GRPC_CPP_PLUGIN gRPC::grpc_cpp_plugin LOCATION)
if(NOT DLMFD_GRPC_CPP_PLUGIN)
  find_program(DLMFD_GRPC_CPP_PLUGIN grpc_cpp_plugin REQUIRED)
endif()

add_custom_command(
  OUTPUT ${API_PB_CC} ${API_PB_H} ${API_GRPC_CC} ${API_GRPC_H}
  COMMAND protobuf::protoc --cpp_out=${PROTO_OUT} --grpc_out=${PROTO_OUT}
          --plugin=protoc-gen-grpc=${DLMFD_GRPC_CPP_PLUGIN}
          -I ${CMAKE_CURRENT_SOURCE_DIR} ${CMAKE_CURRENT_SOURCE_DIR}/${API_PROTO}
  DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/${API_PROTO} ${CMAKE_CURRENT_SOURCE_DIR}/dlmfd/v1/events.proto
          protobuf::protoc)

# The daemon's watch log records (watch_log.proto): its own file format, built with the API it
# holds.
dlmfd_protoc(WATCH_LOG_SRCS dlmfd/v1/watch_log.proto)
# Generated files define names of their own in one namespace: each compiles alone.
set_source_files_properties(${WATCH_LOG_SRCS} PROPERTIES OBJECT_DEPENDS ${API_PB_H}
                            SKIP_UNITY_BUILD_INCLUSION ON)
add_library(dlmfd_api_proto STATIC ${API_PB_CC} ${API_GRPC_CC} ${WATCH_LOG_SRCS})
target_include_directories(dlmfd_api_proto PUBLIC ${PROTO_OUT})
target_link_libraries(dlmfd_api_proto PUBLIC dlmfd_events_proto gRPC::grpc++ protobuf::libprotobuf)
set_target_properties(dlmfd_api_proto PROPERTIES POSITION_INDEPENDENT_CODE ON)
