// Writing the comparison: results.json (docs/interfaces.md fields first), results.csv, the printed
// table and report.md.
#ifndef POOL_COMPARE_RESULTS_IO_H
#define POOL_COMPARE_RESULTS_IO_H

#include <string>
#include <vector>

#include "horizon.h"
#include "metrics.h"

struct json_t;

namespace pool_compare {

/// An error track as a JSON list of [t, error] pairs (a non-finite error as null); new reference.
json_t *track_json(const ErrorTrack &track);

/// Reads track_json's list back (null errors as infinity).
ErrorTrack track_from_json(json_t *list);

/// One record as a compact JSON object (the form results.json and LCM carry).
std::string record_json(const Record &record);

/// One record with its final states (what a run's process sends back to the harness).
std::string record_wire(const Record &record);

/// Reads record_wire's text back; false with *error if it is not such a record.
bool record_from_wire(const std::string &text, Record *record, std::string *error);

/// Writes DIR/results.json; false with *error on I/O failure.
bool write_results_json(const std::string &path, const std::vector<Record> &records, std::string *error);

/// Writes DIR/results.csv with the same columns.
bool write_results_csv(const std::string &path, const std::vector<Record> &records, std::string *error);

/// The readable table; markdown = true gives a markdown table.
std::string results_table(const std::vector<Record> &records, bool markdown);

/// The flight and landing table of the airborne runs ("" when no run has a landing).
std::string landing_table(const std::vector<Record> &records, bool markdown);

/// The persistent-contact (LINK) table: per scenario whose libpool run took link steps or whose
/// reference is not exact, every run's CPU time (median / min), libpool's link share and counts,
/// each engine's final positions against libpool and against the other time-stepped engines at
/// the same step ("" when no such scenario ran).
std::string link_table(const std::vector<Record> &records, bool markdown);

/// Sets consistency_error: each time-stepped run's final positions against the same engine's
/// run at its finest time step in the same scenario (the discretisation part of the error).
void fill_consistency(std::vector<Record> *records);

/// Per scenario and time-stepped engine: the largest time step whose final-position error is at
/// most `tolerance` m, and how much faster libpool is than the engine there (or that it never gets
/// there in the sweep).
std::string accuracy_summary(const std::vector<Record> &records, double tolerance, bool markdown);

/// One line describing the machine (CPU model, cores).
std::string machine_description();

/// Writes report.md: the table, what each engine cannot model, the predictability horizons and
/// the scale comparison (when horizons were measured), and the plots found in DIR.
bool write_report(const std::string &dir, const std::vector<Record> &records, const std::string &command_line,
                  const std::vector<std::string> &plots, std::string *error,
                  const std::vector<ScenarioHorizons> &horizons = {});

} // namespace pool_compare

#endif
