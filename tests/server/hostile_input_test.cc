// Issue 38: the real daemon under 1,200 hostile requests on loopback, every rpc of dlmfd.v1.Jobs:
// request messages filled field by field (through protobuf reflection, so every field of every
// request is reached, repeated ones up to thousands of entries) from a pool of hostile values
// (huge, empty, NUL bytes, control characters, a key of 20,000 dotted parts, TOML nested 300 deep,
// paths that climb out, numbers at their limits, the ids of real jobs and studies), and bodies of
// random or mutated bytes. Every call must end within its deadline with a code the API promises
// (never UNKNOWN, INTERNAL, UNIMPLEMENTED or UNAVAILABLE), and the daemon must be alive, healthy
// and free of sanitizer reports at the end. The seed is fixed: a failure is repeatable.
#include <google/protobuf/descriptor.h>
#include <google/protobuf/reflection.h>
#include <grpcpp/generic/generic_stub.h>
#include <gtest/gtest.h>

#include <signal.h>

#include <chrono>
#include <iostream>
#include <map>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "../support/promised_codes.h"
#include "../support/raw_grpc_call.h"
#include "support/daemon_process.h"

namespace dlmfd::testing {
namespace {

using google::protobuf::FieldDescriptor;
using google::protobuf::Message;

class HostilePool {
 public:
  explicit HostilePool(uint32_t seed)
      : random_(seed) {
    std::string deep_key = "z";
    for (int i = 1; i < 20000; ++i) deep_key += ".z";
    texts_ = {"",
              std::string("a\0b", 3),
              std::string(1 << 20, 'x'),
              std::string(300, '[') + std::string(300, ']'),
              deep_key + " = 1",
              deep_key,
              "fluid.viscosity=" + std::string(5000, '9'),
              "particles.99999999999.density=1",
              "particles.*.density=1.5",
              "*=1",
              "a=b=c",
              "=",
              "time.end=0",
              "time.end=-0.0",
              "particle_mesh.h=1e300",
              "fluid.viscosity=nan",
              "1e309",
              "-9223372036854775808",
              "../../jobs.db",
              "/etc/passwd",
              "summary.json/",
              "fields/../../..",
              "\n\r\t\x01\x7f",
              "\xe2\x80\xae reversed",
              "j-0000000000000000",
              "s-0000000000000000",
              "afterok:j-0000000000000000",
              "fluid.relaxation_time>=1",
              "label/key.ok-1"};
    scenes_ = {CavityScene(0.01),
               CavityScene(1e300),
               deep_key + " = 1\n",
               "[time]\nend = 0\n",
               "[[particles]]\ncenter = [0.5, 0.5]\n[particle_mesh]\nkind = \"ring\"\nh = 1e300\n",
               std::string(1 << 20, '#'),
               "title = \"" + std::string(100000, 'a') + "\"\n"};
  }

  std::mt19937& random() { return random_; }
  size_t Below(size_t n) {
    return n == 0 ? 0 : std::uniform_int_distribution<size_t>(0, n - 1)(random_);
  }
  bool OneIn(size_t n) { return Below(n) == 0; }

  // small: one of many entries of a repeated field (no megabyte texts there).
  std::string Text(const FieldDescriptor* field, bool small) {
    const std::string& name = field->name();
    if (small)
      return OneIn(2) ? texts_[1 + Below(texts_.size() - 1)].substr(0, 64)
                      : "t" + std::to_string(Below(100));
    if (name == "scene" && !OneIn(4)) return scenes_[Below(scenes_.size())];
    if ((name == "job_id" || name == "job_ids") && !jobs_.empty() && !OneIn(3)) {
      return jobs_[Below(jobs_.size())];
    }
    if (name == "study_id" && !studies_.empty() && !OneIn(3))
      return studies_[Below(studies_.size())];
    if (OneIn(4)) return "v" + std::to_string(Below(1000));
    return texts_[Below(texts_.size())];
  }

  int64_t Integer() {
    static const int64_t kValues[] = {0,         1,         -1,     7,       1000,      1001,
                                      -1001,     4096,      4097,   1 << 20, INT32_MAX, INT32_MIN,
                                      INT64_MAX, INT64_MIN, 100000, -100000};
    return kValues[Below(std::size(kValues))];
  }

  double Real() {
    static const double kValues[] = {0.0, -0.0, 1.0, -1.0, 1e300, -1e300, 1e-300, 2.0, 10001.0};
    return kValues[Below(std::size(kValues))];
  }

  void AddJob(const std::string& id) { jobs_.push_back(id); }
  void AddStudy(const std::string& id) { studies_.push_back(id); }

 private:
  std::mt19937 random_;
  std::vector<std::string> texts_, scenes_, jobs_, studies_;
};

// The fields that name what a request acts on: set in a sparse request, so that it gets past the
// first checks to the code behind them.
bool NamesItsSubject(const FieldDescriptor* field) {
  static const std::set<std::string> kNames = {"scene", "job_id", "job_ids", "study_id"};
  return kNames.count(field->name()) > 0;
}

// Fills the fields of the message (nested ones to depth 3), each repeated field with 0 to a few
// thousand entries. sparse: only the subject fields and about one other, so that one hostile
// value at a time meets the handler (a request hostile everywhere is refused at its first field).
void Fill(Message& message, HostilePool& pool, bool sparse, int depth = 0) {
  const auto* descriptor = message.GetDescriptor();
  const auto* reflection = message.GetReflection();
  for (int i = 0; i < descriptor->field_count(); ++i) {
    const FieldDescriptor* field = descriptor->field(i);
    if (sparse ? !NamesItsSubject(field) && !pool.OneIn(descriptor->field_count())
               : pool.OneIn(3)) {
      continue;  // left unset
    }
    const size_t count =
        !field->is_repeated() ? 1 : (pool.OneIn(20) ? 1000 + pool.Below(4000) : pool.Below(4));
    for (size_t n = 0; n < count; ++n) {
      switch (field->cpp_type()) {
        case FieldDescriptor::CPPTYPE_STRING: {
          const std::string text = pool.Text(field, count > 8);
          if (field->is_repeated()) {
            reflection->AddString(&message, field, text);
          } else {
            reflection->SetString(&message, field, text);
          }
          break;
        }
        case FieldDescriptor::CPPTYPE_INT32:
        case FieldDescriptor::CPPTYPE_INT64:
        case FieldDescriptor::CPPTYPE_UINT32:
        case FieldDescriptor::CPPTYPE_UINT64: {
          const int64_t value = pool.Integer();
          if (field->cpp_type() == FieldDescriptor::CPPTYPE_INT32) {
            field->is_repeated()
                ? reflection->AddInt32(&message, field, static_cast<int32_t>(value))
                : reflection->SetInt32(&message, field, static_cast<int32_t>(value));
          } else if (field->cpp_type() == FieldDescriptor::CPPTYPE_INT64) {
            field->is_repeated() ? reflection->AddInt64(&message, field, value)
                                 : reflection->SetInt64(&message, field, value);
          } else if (field->cpp_type() == FieldDescriptor::CPPTYPE_UINT32) {
            field->is_repeated()
                ? reflection->AddUInt32(&message, field, static_cast<uint32_t>(value))
                : reflection->SetUInt32(&message, field, static_cast<uint32_t>(value));
          } else {
            field->is_repeated()
                ? reflection->AddUInt64(&message, field, static_cast<uint64_t>(value))
                : reflection->SetUInt64(&message, field, static_cast<uint64_t>(value));
          }
          break;
        }
        case FieldDescriptor::CPPTYPE_DOUBLE:
          field->is_repeated() ? reflection->AddDouble(&message, field, pool.Real())
                               : reflection->SetDouble(&message, field, pool.Real());
          break;
        case FieldDescriptor::CPPTYPE_FLOAT:
          field->is_repeated()
              ? reflection->AddFloat(&message, field, static_cast<float>(pool.Real()))
              : reflection->SetFloat(&message, field, static_cast<float>(pool.Real()));
          break;
        case FieldDescriptor::CPPTYPE_BOOL:
          field->is_repeated() ? reflection->AddBool(&message, field, pool.OneIn(2))
                               : reflection->SetBool(&message, field, pool.OneIn(2));
          break;
        case FieldDescriptor::CPPTYPE_ENUM: {
          const int value = static_cast<int>(pool.Integer() % 8);
          field->is_repeated() ? reflection->AddEnumValue(&message, field, value)
                               : reflection->SetEnumValue(&message, field, value);
          break;
        }
        case FieldDescriptor::CPPTYPE_MESSAGE:
          if (depth < 3) {
            Message* child = field->is_repeated() ? reflection->AddMessage(&message, field)
                                                  : reflection->MutableMessage(&message, field);
            Fill(*child, pool, sparse, depth + 1);
          }
          break;
      }
    }
  }
}

// A body of random bytes, or a serialized request with bytes flipped, cut or inserted.
std::string MangledBytes(const std::string& body, HostilePool& pool) {
  std::string out = body;
  if (out.empty() || pool.OneIn(3)) {
    out.resize(pool.Below(512));
    for (char& c : out) c = static_cast<char>(pool.Below(256));
    return out;
  }
  for (size_t n = 1 + pool.Below(8); n > 0; --n) {
    const size_t at = pool.Below(out.size());
    switch (pool.Below(3)) {
      case 0:
        out[at] = static_cast<char>(pool.Below(256));
        break;
      case 1:
        out.resize(at);
        break;
      default:
        out.insert(at, 1 + pool.Below(16), static_cast<char>(pool.Below(256)));
    }
    if (out.empty()) break;
  }
  return out;
}

struct Outcome {
  grpc::Status status;
  std::string reply;
  double seconds = 0;
};

// The call and its time (support/raw_grpc_call.h: on a completion queue, for ThreadSanitizer).
Outcome UnaryCall(grpc::GenericStub& stub, const std::string& method, const std::string& body,
                  std::chrono::seconds deadline) {
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + deadline);
  Outcome outcome;
  const auto start = std::chrono::steady_clock::now();
  outcome.status = RawUnaryCall(stub, context, method, body, &outcome.reply);
  outcome.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return outcome;
}

// A server-streaming rpc: Fetch read to its end; Watch read until its first message, the summary
// that shows the daemon answered (a live job's stream lasts as long as the job), then cancelled.
template <class Request, class Reply, class Open>
Outcome StreamCall(const Request& request, bool first_only, Open open) {
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(30));
  const auto start = std::chrono::steady_clock::now();
  auto reader = open(&context, request);
  Outcome outcome;
  outcome.status = ReadStream<Reply>(context, *reader, first_only);
  outcome.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return outcome;
}

TEST(HostileInput, ThousandsOfHostileRequestsNeitherCrashNorHangTheDaemon) {
  if (!SolverAvailable()) GTEST_SKIP() << "dlmfd-solve is not built: " << kSolverPath;
  TempDir dir;
  DaemonProcess daemon(dir.path() + "/data",
                       {"--max-concurrent", "1", "--max-queued", "40", "--max-user-disk-mb", "64"});
  ASSERT_TRUE(daemon.Start()) << daemon.Log();
  auto stub = daemon.Stub();
  grpc::GenericStub generic(daemon.Channel());
  HostilePool pool(38);
  google::protobuf::SetLogHandler(nullptr);  // the client's own parse of mangled bodies complains
  // Real ids to aim at: a finished job, a study.
  {
    v1::SubmitRequest submit;
    submit.set_scene(CavityScene(0.01));
    v1::Job job;
    ASSERT_TRUE(stub->Submit(Context().get(), submit, &job).ok());
    pool.AddJob(job.id());
    v1::SubmitStudyRequest study;
    study.set_scene(CavityScene(0.01));
    auto* axis = study.add_axes();
    axis->set_key("fluid.viscosity");
    axis->add_values("0.01");
    axis->add_values("0.02");
    v1::SubmitStudyResponse swept;
    ASSERT_TRUE(stub->SubmitStudy(Context().get(), study, &swept).ok());
    pool.AddStudy(swept.study_id());
    for (const auto& j : swept.jobs()) pool.AddJob(j.id());
    WaitFinished(*stub, job.id());
  }
  const auto* service = v1::SubmitRequest::descriptor()->file()->FindServiceByName("Jobs");
  ASSERT_NE(service, nullptr);
  constexpr int kRequests = 1200;
  std::map<std::string, std::map<int, int>> codes;  // method -> code -> count
  double slowest = 0;
  for (int i = 0; i < kRequests; ++i) {
    const auto* method = service->method(i % service->method_count());
    const std::string path = "/dlmfd.v1.Jobs/" + method->name();
    std::unique_ptr<Message> request(google::protobuf::MessageFactory::generated_factory()
                                         ->GetPrototype(method->input_type())
                                         ->New());
    Fill(*request, pool, pool.OneIn(2));
    std::string body = request->SerializeAsString();
    const bool mangled = pool.OneIn(3);
    if (mangled) body = MangledBytes(body, pool);
    Outcome outcome;
    v1::WatchRequest watch;
    v1::FetchRequest fetch;
    if (method->name() == "Watch" && watch.ParseFromString(body)) {
      outcome = StreamCall<v1::WatchRequest, v1::WatchEvent>(
          watch, true,
          [&](grpc::ClientContext* c, const v1::WatchRequest& r) { return stub->Watch(c, r); });
    } else if (method->name() == "Fetch" && fetch.ParseFromString(body)) {
      outcome = StreamCall<v1::FetchRequest, v1::FileChunk>(
          fetch, false,
          [&](grpc::ClientContext* c, const v1::FetchRequest& r) { return stub->Fetch(c, r); });
    } else {
      // Unary, or a body that does not parse (the daemon names the request it cannot read).
      outcome = UnaryCall(generic, path, body, std::chrono::seconds(30));
    }
    slowest = std::max(slowest, outcome.seconds);
    ++codes[method->name()][outcome.status.error_code()];
    EXPECT_TRUE(kPromisedCodes.count(outcome.status.error_code()))
        << method->name() << " request " << i << " answered "
        << static_cast<int>(outcome.status.error_code()) << ": "
        << outcome.status.error_message().substr(0, 300);
    if (outcome.status.ok() && method->name() == "Submit") {
      v1::Job job;
      if (job.ParseFromString(outcome.reply)) pool.AddJob(job.id());
    }
    if (outcome.status.ok() && method->name() == "SubmitStudy") {
      v1::SubmitStudyResponse swept;
      if (swept.ParseFromString(outcome.reply)) pool.AddStudy(swept.study_id());
    }
    if (HasFailure()) break;
  }
  EXPECT_TRUE(daemon.Healthy()) << daemon.Log().substr(0, 2000);
  std::string summary;
  for (const auto& [method, by_code] : codes) {
    summary += method + ":";
    for (const auto& [code, count] : by_code) {
      summary += " " + std::to_string(code) + "x" + std::to_string(count);
    }
    summary += "\n";
  }
  std::cout << "hostile requests by rpc and status code (slowest " << slowest << " s):\n"
            << summary;
  EXPECT_EQ(codes.size(), static_cast<size_t>(service->method_count()));
  daemon.Kill(SIGTERM);
  EXPECT_EQ(daemon.Wait(), 0) << "the daemon did not stop cleanly";
}

}  // namespace
}  // namespace dlmfd::testing
