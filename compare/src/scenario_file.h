// A scenario of the comparison: the libpool-scenario/1 text handed to every plugin, and its
// parsed form (tools/common/scenario.h) the harness uses for references and metrics.
#ifndef POOL_COMPARE_SCENARIO_FILE_H
#define POOL_COMPARE_SCENARIO_FILE_H

#include <memory>
#include <string>

extern "C" {
#include "pool/scenario.h"
}

namespace pool_compare {

/// One scenario: name (file stem), JSON text and parsed, validated content.
struct Scenario {
	std::string path;        ///< file it came from ("" for text)
	std::string name;        ///< file stem, the "scenario" field of results
	std::string json;        ///< the document as given to the plugins
	pool_scenario parsed{};  ///< owned, freed by the destructor
	std::string family;      ///< scale family of a generated scenario (scale_scenarios.h), else ""

	Scenario() = default;
	Scenario(const Scenario &) = delete;
	Scenario &operator=(const Scenario &) = delete;
	~Scenario() { pool_scenario_free(&parsed); }

	/// Index of a ball id in parsed.balls, or -1.
	int index_of(int id) const;
	/// The ball a perturbation study moves: the struck ball, else the fastest one.
	int lead_ball_id() const;
};

/// Reads and validates a file; false with "FILE: <parser message>" in *error.
bool load_scenario(const std::string &path, std::unique_ptr<Scenario> *out, std::string *error);

/// Validates a document given as text.
bool parse_scenario(const std::string &name, const std::string &json, std::unique_ptr<Scenario> *out,
                    std::string *error);

/// The same document with ball `id` moved by (dx, dy) m on the cloth. "" on failure.
std::string perturbed_json(const std::string &json, int id, double dx, double dy);

/// The same document with every ball moved by `distance` m on the cloth, ball k (in the list) in
/// the direction of angle 2 pi frac(turn + k / golden ratio). "" on failure.
std::string perturbed_all_json(const std::string &json, double distance, double turn);

} // namespace pool_compare

#endif
