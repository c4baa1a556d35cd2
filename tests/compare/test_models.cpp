// The optional models (issue 12, docs/physics.md "Models") in the comparison harness:
// scenarios with "models" load (bad ones refused naming the field); the libpool plugin simulates
// the scenario's models (its run equals the libpool reference of the same scenario, and differs
// from the default models' one); the ODE and Bullet plugins say which models they cannot
// express, which every record carries as "unsupported_models" (null for a plugin that does not
// say), through the child-process wire too; the closed forms step aside when squirt changes the
// strike.
// usage: test_models PLUGIN_DIR ENGINE...   (the engines that must exist)
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <jansson.h>

#include "metrics.h"
#include "plugin_loader.h"
#include "reference.h"
#include "results_io.h"
#include "runner.h"
#include "scenario_file.h"

#include "compare_test.h"

using namespace pool_compare;
using namespace compare_test;

namespace {

// A cut with side whose balls go on into cushions (every model changes it), with the given models
// (none: the library's defaults, issue 25's measured laws).
std::string cut_with(const std::string &models) {
	return std::string("{\"format\": \"libpool-scenario/1\",") + models +
	       " \"params\": {\"throw_a\": 0.012, \"cue_end_mass\": 0.1},"
	       " \"balls\": [{\"id\": 0, \"pos\": [1.0, 0.5]}, {\"id\": 1, \"pos\": [1.5, 0.62]}],"
	       " \"strike\": {\"ball\": 0, \"speed\": 2.2, \"phi\": 12, \"a\": 0.011, \"b\": -0.004},"
	       " \"options\": {\"max_time\": 30}}";
}

const std::string kAllModels =
	" \"models\": {\"cushion\": \"mathavan2010\", \"ball_ball_friction\": \"alciatore\", \"squirt\": \"endmass\"},";
const std::vector<std::string> kAllNames = {"cushion=mathavan2010", "ball_ball_friction=alciatore",
                                            "squirt=endmass"};
// The laws ODE and Bullet express: the 2012 work's (the comparison's scenarios pin them).
const std::string kThesis = " \"models\": \"thesis\",";

std::string joined(const std::vector<std::string> &list) {
	std::string s;
	for (const std::string &x : list)
		s += (s.empty() ? "" : ",") + x;
	return s;
}

void bad_models_are_refused() {
	std::unique_ptr<Scenario> s;
	std::string error;
	CHECK(!parse_scenario("bad", cut_with(" \"models\": {\"cushion\": \"rubber\"},"), &s, &error), "accepted");
	CHECK(error == "bad: models.cushion: unknown model \"rubber\" (petit, mathavan2010)", "%s", error.c_str());
	CHECK(!parse_scenario("bad", cut_with(" \"models\": {\"spin\": \"none\"},"), &s, &error), "accepted");
	CHECK(error == "bad: models.spin: unknown field", "%s", error.c_str());
}

// Squirt turns an off-centre strike: the closed form (docs/physics.md "Cue strike" without it) must
// not be the reference then; a centred strike, or no squirt, keeps it.
void closed_form_steps_aside_for_squirt() {
	auto one_ball = [](const char *models, double a) {
		char text[512];
		std::snprintf(text, sizeof text,
		              "{\"format\": \"libpool-scenario/1\",%s \"balls\": [{\"id\": 0, \"pos\": [1.27, 0.635]}],"
		              " \"strike\": {\"ball\": 0, \"speed\": 0.25, \"a\": %g}}",
		              models, a);
		return from_text("one_ball", text);
	};
	const char *squirt = " \"models\": {\"squirt\": \"endmass\"},";
	auto with = one_ball(squirt, 0.01), centred = one_ball(squirt, 0.0), without = one_ball("", 0.01);
	auto cushion = one_ball(" \"models\": {\"cushion\": \"mathavan2010\"},", 0.01);
	if (!with || !centred || !without || !cushion)
		return;
	CHECK(make_closed_form_reference(*with) == nullptr, "closed form taken for a squirted strike");
	CHECK(make_closed_form_reference(*centred) != nullptr, "no closed form for a centred strike");
	CHECK(make_closed_form_reference(*without) != nullptr, "no closed form without squirt");
	CHECK(make_closed_form_reference(*cushion) != nullptr, "no closed form for a shot far from cushions");
}

void engine_says_what_it_lacks(const Plugin &plugin) {
	const std::string name = plugin.api->name;
	auto all = from_text("cut_models", cut_with(kAllModels));
	auto cushion = from_text("cut_cushion", cut_with(" \"models\": {\"set\": \"thesis\", \"cushion\": \"mathavan2010\"},"));
	auto plain = from_text("cut", cut_with(kThesis));
	auto defaults = from_text("cut_defaults", cut_with(""));
	if (!all || !cushion || !plain || !defaults)
		return;
	std::vector<std::string> lacks;
	const bool says = unsupported_models(*all, plugin, &lacks);
	CHECK(says, "%s: no %s export", name.c_str(), POOL_ENGINE_MODELS_ENTRY);
	const std::vector<std::string> expect_all =
		name == "libpool" ? std::vector<std::string>() : kAllNames;
	CHECK(lacks == expect_all, "%s lacks [%s], expected [%s]", name.c_str(), joined(lacks).c_str(),
	      joined(expect_all).c_str());
	unsupported_models(*cushion, plugin, &lacks);
	CHECK(lacks == (name == "libpool" ? std::vector<std::string>() : std::vector<std::string>{"cushion=mathavan2010"}),
	      "%s lacks [%s] with the cushion model alone", name.c_str(), joined(lacks).c_str());
	unsupported_models(*plain, plugin, &lacks);
	CHECK(lacks.empty(), "%s lacks [%s] with the thesis models", name.c_str(), joined(lacks).c_str());
	unsupported_models(*defaults, plugin, &lacks);
	CHECK(lacks == (name == "libpool" ? std::vector<std::string>()
	                                  : std::vector<std::string>{"cushion=mathavan2010", "ball_ball_friction=alciatore"}),
	      "%s lacks [%s] with the library's default models", name.c_str(), joined(lacks).c_str());
	char out[64] = "x";
	CHECK(plugin.unsupported_models && plugin.unsupported_models("{", out, sizeof out) == (name == "libpool" ? 0 : -1),
	      "%s: a broken scenario gives %s", name.c_str(), out);

	// The records say it, in results.json and through the child-process wire.
	std::string error;
	auto ref = make_libpool_reference(*all, &error);
	CHECK(ref != nullptr, "reference: %s", error.c_str());
	if (!ref)
		return;
	RunSettings settings;
	settings.dt = 1e-3;
	settings.min_timing_cpu = 0.0;
	const Record blank = blank_record(*all, *ref, plugin, settings);
	CHECK(blank.models_known && blank.unsupported_models == expect_all, "%s record: [%s]", name.c_str(),
	      joined(blank.unsupported_models).c_str());
	// In the record's JSON: the list, by name.
	json_t *o = json_loads(record_json(blank).c_str(), 0, nullptr);
	json_t *field = json_object_get(o, "unsupported_models");
	std::vector<std::string> written;
	for (size_t i = 0; i < json_array_size(field); ++i)
		written.push_back(json_string_value(json_array_get(field, i)));
	CHECK(json_is_array(field) && written == expect_all, "%s: results.json has [%s]", name.c_str(),
	      joined(written).c_str());
	json_decref(o);
	Record back;
	CHECK(record_from_wire(record_wire(blank), &back, &error), "%s", error.c_str());
	CHECK(back.models_known && back.unsupported_models == blank.unsupported_models, "%s: wire lost [%s]",
	      name.c_str(), joined(blank.unsupported_models).c_str());
	std::printf("  %s cannot express: [%s]\n", name.c_str(), joined(lacks.empty() ? expect_all : lacks).c_str());
}

// The libpool plugin simulates the scenario's models: its run is the libpool reference of the
// same scenario (errors zero), and differs from the thesis models' reference.
void libpool_runs_the_models(const Plugin &libpool) {
	auto all = from_text("cut_models", cut_with(kAllModels));
	if (!all)
		return;
	std::string error;
	auto ref = make_libpool_reference(*all, &error);
	CHECK(ref != nullptr, "reference: %s", error.c_str());
	if (!ref)
		return;
	RunSettings settings;
	settings.min_timing_cpu = 0.0;
	const Record same = run_engine(*all, *ref, libpool, settings);
	CHECK(same.error.empty() && same.final_position_error == 0.0 && same.missed_collisions == 0 &&
	          same.phantom_collisions == 0,
	      "libpool with models vs its reference: %s, final error %g m", same.error.c_str(), same.final_position_error);
	// And the models matter: against the default models' reference of the same shot the final
	// positions differ by far more than rounding (~1e-15 m on a table; the models move balls by
	// centimetres), so the plugin did not drop them on the way.
	auto plain = from_text("cut", cut_with(kThesis));
	auto ref_plain = plain ? make_libpool_reference(*plain, &error) : nullptr;
	CHECK(ref_plain != nullptr, "thesis reference: %s", error.c_str());
	if (!ref_plain)
		return;
	const double kModelsMatter = 1e-6; // m
	const Record other = run_engine(*all, *ref_plain, libpool, settings);
	CHECK(other.error.empty() && other.final_position_error > kModelsMatter,
	      "the models changed nothing: final error %g m against the thesis models", other.final_position_error);
	std::printf("  libpool: models vs thesis models, final positions %.3g m apart\n", other.final_position_error);
}

// A plugin without the export: the record says nothing ("unsupported_models": null).
void silent_plugin_is_null(const Plugin &plugin) {
	Plugin silent = plugin;
	silent.unsupported_models = nullptr;
	auto all = from_text("cut_models", cut_with(kAllModels));
	std::string error;
	auto ref = all ? make_libpool_reference(*all, &error) : nullptr;
	if (!ref)
		return;
	const Record r = blank_record(*all, *ref, silent, RunSettings());
	CHECK(!r.models_known && r.unsupported_models.empty(), "silent plugin known");
	json_t *o = json_loads(record_json(r).c_str(), 0, nullptr);
	CHECK(json_is_null(json_object_get(o, "unsupported_models")), "%s", record_json(r).c_str());
	json_decref(o);
}

} // namespace

int main(int argc, char **argv) {
	if (argc < 2) {
		std::fprintf(stderr, "usage: test_models PLUGIN_DIR ENGINE...\n");
		return 2;
	}
	bad_models_are_refused();
	closed_form_steps_aside_for_squirt();
	for (const Plugin &plugin : load_plugins(argc, argv, 2, argv[1])) {
		engine_says_what_it_lacks(plugin);
		if (std::string(plugin.api->name) == "libpool") {
			libpool_runs_the_models(plugin);
			silent_plugin_is_null(plugin);
		}
	}
	return finish();
}
