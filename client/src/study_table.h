// A study as a table: the rows of the Table rpc (jobs.proto) flattened into named columns, the
// same for `dlmfd table` (CSV, JSON) and `dlmfd chart --study` (a column against a parameter).
//
// Columns, in this order: job, name, state, one per parameter key (the overrides, typed; in the
// order first met), then status, reason, steps, time, wall_seconds, fall_speed, min_gap,
// min_wall_gap, max_trA, min_eig_A, Re, De, E, M, and per particle N (in the order of the rows'
// particles) pN.radius, pN.x, pN.y, pN.u, pN.v, pN.omega, pN.fx, pN.fy, pN.torque, pN.fall_speed.
// A cell is empty (JSON null) where a row has no value: no summary yet, NaN, a parameter another
// job does not have, a particle another job does not have.
#pragma once

#include <cstdint>
#include <string>
#include <variant>
#include <vector>

#include "connection.h"
#include "dlmfd/v1/jobs.pb.h"

namespace dlmfd::cli {

// Empty, an integer (int64 stays an integer), a double, a boolean or a text.
using TableCell = std::variant<std::monostate, int64_t, double, bool, std::string>;

struct StudyTable {
  std::vector<std::string> columns;
  std::vector<std::vector<TableCell>> rows;  // each as long as columns

  // The index of a column; throws UsageError naming the columns when there is none.
  size_t Column(const std::string& name, const std::string& flag) const;
  // Only the named columns, in that order (UsageError for an unknown one).
  StudyTable Select(const std::vector<std::string>& names) const;
};

// The rows of a study (study_id non-empty) or of the named jobs; throws UsageError or returns
// the rpc's status through *status.
grpc::Status FetchTableRows(Connection& connection, const std::string& study_id,
                            const std::vector<std::string>& job_ids, v1::TableResponse* out);
StudyTable FlattenTable(const v1::TableResponse& response);

// CSV with a header line (RFC 4180 quoting); numbers as the shortest text that reads back as the
// same double, empty cells empty.
std::string TableCsv(const StudyTable& table);
// A JSON array of objects, one per row, keys in column order; integers as integers, null for empty.
std::string TableJson(const StudyTable& table);
// The cell as a number: integers and doubles, booleans as 0/1; NaN otherwise.
double CellNumber(const TableCell& cell);

}  // namespace dlmfd::cli
