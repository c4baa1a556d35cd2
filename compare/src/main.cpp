// pool-compare: measures engine plugins against the closed forms and libpool on shared scenarios
// (docs/interfaces.md, docs/engines.md).
#include <dirent.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "isolation.h"
#include "lcm_publish.h"
#include "plugin_loader.h"
#include "reference.h"
#include "results_io.h"
#include "runner.h"
#include "text_table.h"
#include "scale_report.h"
#include "scale_scenarios.h"
#include "scenario_file.h"

using namespace pool_compare;

namespace {

const char kUsage[] =
    "usage: pool-compare [--scenario FILE ...] [--engines libpool,ode,bullet] [--dt 1e-3,1e-4]\n"
    "                    [--out DIR] [--lcm-url URL] [--plugin-dir DIR] [--spread N]\n"
    "                    [--airborne] [--link] [--scale N,N,...] [--families LIST]\n"
    "                    [--repeat N] [--timeout S] [--in-process]\n"
    "                    [--python PATH] [--no-plots]\n"
    "                    [--quiet]\n"
    "                    [--help]\n"
    "\n"
    "Runs each scenario on each engine plugin at each time step and measures it against the\n"
    "closed form (one ball on the cloth) or libpool's exact result. Writes DIR/results.json,\n"
    "DIR/results.csv, plots (DIR/*.png) and DIR/report.md, and prints the table. What the\n"
    "engines themselves print goes to DIR/engines.log. Each run (scenario, engine, step) runs in\n"
    "a child process of its own: one that crashes, calls exit, hangs past --timeout or gives back\n"
    "non-finite or miscounted states is an error row (its reason in the error field, e.g.\n"
    "\"killed by SIGSEGV\", \"exit(3)\", \"timed out after 600 s\") and the others go on.\n"
    "results.json, results.csv and report.md are rewritten (atomically) after every run.\n"
    "Scenarios of 3 or more balls with a libpool reference also get a predictability horizon:\n"
    "the time until each run departs 1 cm from libpool, beside libpool against itself with its\n"
    "start 1 nm, 1 um and 1 mm off (DIR/horizon.json, DIR/<scenario>_horizon.png).\n"
    "\n"
    "  --scenario FILE  libpool-scenario/1 file; repeat it or list several files after it\n"
    "                   (default: every compare/scenarios/*.json)\n"
    "  --airborne       the airborne scenarios, compare/scenarios/airborne/*.json (jump, masse,\n"
    "                   cushion hop, drop, hop), instead of the default set or after the\n"
    "                   --scenario files; not in the default set (they take longer); each is\n"
    "                   scored against its airborne closed form where it has one, else against\n"
    "                   libpool's result (options.airborne)\n"
    "  --link           the persistent-contact (LINK) scenarios, compare/scenarios/link/*.json\n"
    "                   (push, rest_on_two, slide_off, airborne_break), like --airborne; their\n"
    "                   reference is libpool's result with LINK steps, which is not exact\n"
    "                   (\"reference_exact\": false): the errors are the engines' disagreement;\n"
    "                   libpool's rows say what share of its time went to link steps\n"
    "  --scale LIST     also run the scale families at these ball counts (e.g. 16,64,256,1024;\n"
    "                   2 to 4096): a break on a table of N / 16 standard areas and a gas of\n"
    "                   balls, a quarter of them rolling (written to DIR/scenarios/); reported as\n"
    "                   CPU per simulated second against N at equal predictability; a benchmark\n"
    "                   (the 1,024-ball runs at dt 1e-5 take minutes each)\n"
    "  --families LIST  the scale families to run: break, gas (default both)\n"
    "  --repeat N       time every run at least N times (median and minimum reported; default 1,\n"
    "                   short runs are repeated anyway until 0.2 s of CPU): a benchmark\n"
    "  --engines LIST   plugin names or paths to .so modules, comma-separated; a name loads\n"
    "                   <plugin dir>/libpool_engine_<name>.so (default: libpool,ode,bullet,\n"
    "                   those that are built)\n"
    "  --dt LIST        time steps of time-stepped engines, s (default 1e-2,1e-3,1e-4,1e-5)\n"
    "  --out DIR        output directory (default out/compare)\n"
    "  --lcm-url URL    also publish each result as pool_lcm.bench_result_t on POOL_BENCH\n"
    "  --plugin-dir DIR where plugin names are looked up (default: next to pool-compare)\n"
    "  --spread N       perturbed runs (1 um moves of the lead ball) measuring the spread of\n"
    "                   outcomes in scenarios of 3 or more balls (default 8, 0 = off; the\n"
    "                   default sweep skips them below dt 1e-4, a --dt list does not; scale\n"
    "                   scenarios have none: their predictability is the horizon)\n"
    "  --timeout S      wall-clock limit of one run (measured run, timing repetitions and\n"
    "                   perturbed runs together), s; the run is killed past it (default 600,\n"
    "                   0 = none)\n"
    "  --in-process     run the plugins inside pool-compare, unprotected (for a debugger)\n"
    "  --python PATH    Python with matplotlib for the plots (default: the repo's .venv)\n"
    "  --no-plots       skip the plots\n"
    "  --quiet          no progress lines\n"
    "\n"
    "Exit status: 0 every run done; 1 some run failed (its error row is in every output, which\n"
    "are all written; the failed runs are listed on standard error) or an output file could not\n"
    "be written; 2 bad option, scenario or plugin (message on standard error).\n";

struct Options {
	std::vector<std::string> scenarios;
	std::vector<std::string> engines;
	bool engines_given = false;
	std::vector<double> dts = {1e-2, 1e-3, 1e-4, 1e-5};
	bool dts_given = false;
	std::string out = "out/compare";
	std::string lcm_url;
	std::string plugin_dir;
	int spread = 8;
	double timeout = 600.0;
	bool in_process = false;
	std::string python;
	bool plots = true;
	bool quiet = false;
	bool airborne = false;
	bool link = false;
	int repeat = 1;
	std::vector<int> scale;  ///< ball counts of the scale families (empty: none)
	std::vector<std::string> families = scale_families();
};

int usage_error(const std::string &message) {
	std::cerr << "pool-compare: " << message << "\n(see pool-compare --help)\n";
	return 2;
}

std::vector<std::string> split(const std::string &list) {
	std::vector<std::string> out;
	std::stringstream in(list);
	std::string item;
	while (std::getline(in, item, ','))
		if (!item.empty())
			out.push_back(item);
	return out;
}

bool parse_double(const std::string &text, double *out) {
	if (text.empty())
		return false;
	char *end = nullptr;
	errno = 0;
	const double x = std::strtod(text.c_str(), &end);
	if (errno || *end != '\0' || !std::isfinite(x))
		return false;
	*out = x;
	return true;
}

std::string executable_dir() {
	char buf[4096];
	const ssize_t n = readlink("/proc/self/exe", buf, sizeof buf - 1);
	if (n <= 0)
		return ".";
	std::string path(buf, static_cast<size_t>(n));
	return path.substr(0, path.find_last_of('/'));
}

bool is_dir(const std::string &path) {
	struct stat st;
	return stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode);
}

bool make_dirs(const std::string &path) {
	std::string sofar;
	std::stringstream in(path);
	std::string part;
	if (!path.empty() && path[0] == '/')
		sofar = "/";
	while (std::getline(in, part, '/')) {
		if (part.empty())
			continue;
		sofar += part + "/";
		if (mkdir(sofar.c_str(), 0777) != 0 && errno != EEXIST)
			return false;
	}
	return is_dir(path);
}

std::vector<std::string> default_scenarios(const std::string &dir) {
	std::vector<std::string> files;
	if (DIR *d = opendir(dir.c_str())) {
		while (const dirent *e = readdir(d)) {
			const std::string name = e->d_name;
			if (name.size() > 5 && name.compare(name.size() - 5, 5, ".json") == 0)
				files.push_back(dir + "/" + name);
		}
		closedir(d);
	}
	std::sort(files.begin(), files.end());
	return files;
}

// Parses argv; returns -1 to go on, else the exit status.
int parse_args(int argc, char **argv, Options *o) {
	bool in_scenarios = false;
	for (int i = 1; i < argc; ++i) {
		const std::string arg = argv[i];
		auto value = [&](std::string *out) {
			if (i + 1 >= argc)
				return false;
			*out = argv[++i];
			return true;
		};
		std::string v;
		if (arg == "--help" || arg == "-h") {
			std::cout << kUsage;
			return 0;
		} else if (arg == "--scenario") {
			if (!value(&v))
				return usage_error("--scenario needs a file");
			o->scenarios.push_back(v);
			in_scenarios = true;
			continue;
		} else if (arg == "--engines") {
			if (!value(&v) || split(v).empty())
				return usage_error("--engines needs a comma-separated list of plugin names or paths");
			o->engines = split(v);
			o->engines_given = true;
		} else if (arg == "--dt") {
			if (!value(&v) || split(v).empty())
				return usage_error("--dt needs a comma-separated list of time steps in seconds");
			o->dts.clear();
			for (const std::string &item : split(v)) {
				double dt;
				if (!parse_double(item, &dt) || !(dt > 0.0) || dt > 1.0)
					return usage_error("--dt: '" + item + "' is not a time step in (0, 1] s");
				o->dts.push_back(dt);
			}
			o->dts_given = true;
		} else if (arg == "--out") {
			if (!value(&v) || v.empty())
				return usage_error("--out needs a directory");
			o->out = v;
		} else if (arg == "--lcm-url") {
			if (!value(&v) || v.empty())
				return usage_error("--lcm-url needs a URL");
			o->lcm_url = v;
		} else if (arg == "--plugin-dir") {
			if (!value(&v) || v.empty())
				return usage_error("--plugin-dir needs a directory");
			if (!is_dir(v))
				return usage_error("--plugin-dir: '" + v + "' is not a directory");
			o->plugin_dir = v;
		} else if (arg == "--spread") {
			double n;
			if (!value(&v) || !parse_double(v, &n) || n < 0 || n > 1000 || n != static_cast<int>(n))
				return usage_error("--spread needs a whole number of runs in [0, 1000]");
			o->spread = static_cast<int>(n);
		} else if (arg == "--timeout") {
			double t;
			if (!value(&v) || !parse_double(v, &t) || t < 0)
				return usage_error("--timeout needs a time limit in seconds (0 = none)");
			o->timeout = t;
		} else if (arg == "--airborne") {
			o->airborne = true;
		} else if (arg == "--link") {
			o->link = true;
		} else if (arg == "--scale") {
			if (!value(&v) || split(v).empty())
				return usage_error("--scale needs a comma-separated list of ball counts");
			o->scale.clear();
			for (const std::string &item : split(v)) {
				double n;
				if (!parse_double(item, &n) || n != static_cast<int>(n) || n < 2 || n > kScaleMaxBalls)
					return usage_error("--scale: '" + item + "' is not a ball count in [2, " +
					                   std::to_string(kScaleMaxBalls) + "]");
				o->scale.push_back(static_cast<int>(n));
			}
		} else if (arg == "--families") {
			if (!value(&v) || split(v).empty())
				return usage_error("--families needs a comma-separated list of scale families (break, gas)");
			o->families.clear();
			for (const std::string &item : split(v)) {
				const std::vector<std::string> &known = scale_families();
				if (std::find(known.begin(), known.end(), item) == known.end())
					return usage_error("--families: unknown family '" + item + "' (break, gas)");
				o->families.push_back(item);
			}
		} else if (arg == "--repeat") {
			double n;
			if (!value(&v) || !parse_double(v, &n) || n < 1 || n > 10000 || n != static_cast<int>(n))
				return usage_error("--repeat needs a whole number of timed runs in [1, 10000]");
			o->repeat = static_cast<int>(n);
		} else if (arg == "--in-process") {
			o->in_process = true;
		} else if (arg == "--python") {
			if (!value(&v) || v.empty())
				return usage_error("--python needs a path");
			o->python = v;
		} else if (arg == "--no-plots") {
			o->plots = false;
		} else if (arg == "--quiet") {
			o->quiet = true;
		} else if (!arg.empty() && arg[0] != '-' && in_scenarios) {
			o->scenarios.push_back(arg);
			continue;
		} else if (!arg.empty() && arg[0] == '-') {
			return usage_error("unknown option '" + arg + "'");
		} else {
			return usage_error("unexpected argument '" + arg + "' (scenario files follow --scenario)");
		}
		in_scenarios = false;
	}
	return -1;
}

// Engines print diagnostics of their own (ODE's "LCP internal error", ...) straight to standard
// error; while an engine runs, its standard error goes to DIR/engines.log instead, so the table
// stays readable, and the record counts the lines.
class EngineLog {
public:
	explicit EngineLog(const std::string &path) : fd_(open(path.c_str(), O_CREAT | O_TRUNC | O_RDWR, 0644)) {}
	~EngineLog() {
		if (fd_ >= 0)
			close(fd_);
	}
	template <typename F>
	int capture(const std::string &title, F run) {
		if (fd_ < 0) {
			run();
			return 0;
		}
		const std::string header = "== " + title + "\n";
		if (write(fd_, header.data(), header.size()) < 0)
			return 0;
		const off_t start = lseek(fd_, 0, SEEK_END);
		std::fflush(stderr);
		const int saved = dup(2);
		dup2(fd_, 2);
		run();
		std::fflush(stderr);
		dup2(saved, 2);
		close(saved);
		const off_t end = lseek(fd_, 0, SEEK_END);
		int lines = 0;
		std::vector<char> text(static_cast<size_t>(end - start));
		if (!text.empty() && pread(fd_, text.data(), text.size(), start) == static_cast<ssize_t>(text.size()))
			lines = static_cast<int>(std::count(text.begin(), text.end(), '\n'));
		return lines;
	}

private:
	int fd_;
};

std::string fmt_dt(double dt) {
	char buf[32];
	std::snprintf(buf, sizeof buf, "%.0e", dt);
	return buf;
}

// Runs the plot script; returns the PNG file names it reports (relative to the output dir).
std::vector<std::string> draw_plots(const Options &o) {
	std::string python = o.python;
	if (python.empty())
		python = access(POOL_COMPARE_DEFAULT_PYTHON, X_OK) == 0 ? POOL_COMPARE_DEFAULT_PYTHON : "python3";
	const std::string command = "'" + python + "' '" POOL_COMPARE_PLOT_SCRIPT "' '" + o.out + "/results.json' '" +
	                            o.out + "'";
	std::vector<std::string> plots;
	FILE *pipe = popen(command.c_str(), "r");
	if (!pipe) {
		std::cerr << "pool-compare: warning: cannot run " << command << "\n";
		return plots;
	}
	char line[1024];
	while (std::fgets(line, sizeof line, pipe)) {
		std::string name = line;
		while (!name.empty() && (name.back() == '\n' || name.back() == '\r'))
			name.pop_back();
		if (name.size() > 4 && name.compare(name.size() - 4, 4, ".png") == 0)
			plots.push_back(name);
	}
	if (pclose(pipe) != 0)
		std::cerr << "pool-compare: warning: the plot script failed (" << command << "); report without plots\n";
	return plots;
}

} // namespace

int main(int argc, char **argv) {
	Options o;
	const int parsed = parse_args(argc, argv, &o);
	if (parsed >= 0)
		return parsed;

	if (o.plugin_dir.empty()) {
		const std::string beside = executable_dir() + "/plugins";
		o.plugin_dir = is_dir(beside) ? beside : POOL_COMPARE_DEFAULT_PLUGIN_DIR;
	}
	if (!o.engines_given) {
		const std::vector<std::string> present = available_plugins(o.plugin_dir);
		for (const char *name : {"libpool", "ode", "bullet"}) {
			if (std::find(present.begin(), present.end(), name) != present.end())
				o.engines.push_back(name);
			else
				std::cerr << "pool-compare: warning: engine '" << name << "' is not built (no "
				          << plugin_module_path(name, o.plugin_dir) << "); skipped\n";
		}
		if (o.engines.empty())
			return usage_error("no engine plugin found in " + o.plugin_dir + " (pass --plugin-dir or --engines)");
	}

	std::vector<Plugin> plugins;
	for (const std::string &request : o.engines) {
		Plugin p;
		std::string error;
		if (!load_plugin(request, o.plugin_dir, &p, &error)) {
			std::cerr << "pool-compare: " << error << "\n";
			return 2;
		}
		plugins.push_back(p);
	}

	if (o.airborne) {
		const std::vector<std::string> air = default_scenarios(POOL_COMPARE_DEFAULT_SCENARIO_DIR "/airborne");
		if (air.empty())
			return usage_error("--airborne: no scenario files in " POOL_COMPARE_DEFAULT_SCENARIO_DIR "/airborne");
		o.scenarios.insert(o.scenarios.end(), air.begin(), air.end());
	}
	if (o.link) {
		const std::vector<std::string> link = default_scenarios(POOL_COMPARE_DEFAULT_SCENARIO_DIR "/link");
		if (link.empty())
			return usage_error("--link: no scenario files in " POOL_COMPARE_DEFAULT_SCENARIO_DIR "/link");
		o.scenarios.insert(o.scenarios.end(), link.begin(), link.end());
	}
	if (o.scenarios.empty() && o.scale.empty()) {
		o.scenarios = default_scenarios(POOL_COMPARE_DEFAULT_SCENARIO_DIR);
		if (o.scenarios.empty())
			return usage_error("no scenario files in " POOL_COMPARE_DEFAULT_SCENARIO_DIR);
	}
	std::vector<std::unique_ptr<Scenario>> scenarios;
	for (const std::string &file : o.scenarios) {
		std::unique_ptr<Scenario> s;
		std::string error;
		if (!load_scenario(file, &s, &error)) {
			std::cerr << "pool-compare: " << error << "\n";
			return 2;
		}
		scenarios.push_back(std::move(s));
	}

	// The scale families, generated here and written to DIR/scenarios/ (pool-sim runs them too).
	std::vector<std::pair<std::string, std::string>> generated; // file name, text
	for (const std::string &family : o.families)
		for (int n : o.scale) {
			std::string json, error;
			std::unique_ptr<Scenario> s;
			const std::string name = scale_scenario_name(family, n);
			if (!scale_scenario_json(family, n, &json, &error) || !parse_scenario(name, json, &s, &error)) {
				std::cerr << "pool-compare: " << error << "\n";
				return 2;
			}
			s->family = family;
			scenarios.push_back(std::move(s));
			generated.push_back({name + ".json", json});
		}

	std::unique_ptr<BenchPublisher> publisher;
	if (!o.lcm_url.empty()) {
		std::string error;
		publisher = BenchPublisher::open(o.lcm_url, &error);
		if (!publisher) {
			std::cerr << "pool-compare: " << error << "\n";
			return 2;
		}
	}
	if (!make_dirs(o.out)) {
		std::cerr << "pool-compare: --out: cannot create directory '" << o.out << "'\n";
		return 2;
	}

	if (!generated.empty()) {
		if (!make_dirs(o.out + "/scenarios")) {
			std::cerr << "pool-compare: --out: cannot create directory '" << o.out << "/scenarios'\n";
			return 2;
		}
		for (const auto &[file, json] : generated) {
			std::string error;
			if (!write_file(o.out + "/scenarios/" + file, json + "\n", &error)) {
				std::cerr << "pool-compare: " << error << "\n";
				return 2;
			}
		}
	}

	std::string command_line = "pool-compare";
	for (int i = 1; i < argc; ++i)
		command_line += std::string(" ") + argv[i];

	int status = 0;
	std::vector<Record> records;
	std::vector<ScenarioHorizons> horizons;
	EngineLog engine_log(o.out + "/engines.log");
	// Every finished run is on disk at once: a harness that dies later loses none of them.
	bool save_failed = false;
	auto save = [&](const std::vector<std::string> &plots) {
		fill_consistency(&records);
		std::string error;
		if (write_results_json(o.out + "/results.json", records, &error) &&
		    write_results_csv(o.out + "/results.csv", records, &error) &&
		    (horizons.empty() || write_horizon_json(o.out + "/horizon.json", records, horizons, &error)) &&
		    write_report(o.out, records, command_line, plots, &error, horizons))
			return true;
		if (!save_failed)
			std::cerr << "pool-compare: " << error << "\n";
		save_failed = true;
		return false;
	};
	for (const auto &scenario : scenarios) {
		std::string error;
		std::unique_ptr<Reference> ref = make_closed_form_reference(*scenario);
		if (!ref)
			ref = make_airborne_closed_form_reference(*scenario);
		if (!ref)
			ref = make_libpool_reference(*scenario, &error);
		if (!ref) {
			// No ground truth (libpool refused the scenario): the engines still run, their rows
			// say "no reference", and the harness exits 1.
			std::cerr << "pool-compare: " << error << " (no reference: the engines run, nothing is scored)\n";
			status = 1;
			ref = make_no_reference(*scenario, error);
		}
		const bool many_balls = scenario->parsed.ball_count >= 3;
		// A chaotic scene's predictability: libpool against itself here, each run in run_engine.
		std::vector<double> track_times;
		if (horizon_applies(*scenario, *ref)) {
			ScenarioHorizons h;
			h.scenario = scenario->name;
			h.balls = scenario->parsed.ball_count;
			h.family = scenario->family;
			h.end_time = ref->end_time;
			const double t0 = cpu_now();
			if (!self_horizons(*scenario, *ref, &h.self, &error)) {
				std::cerr << "pool-compare: " << error << " (no horizons)\n";
				status = 1;
			} else {
				track_times = horizon_times(ref->end_time);
				if (!o.quiet)
					std::cerr << "  " << scenario->name << " / libpool against itself: horizons "
					          << h.self[0].horizon.seconds << ", " << h.self[1].horizon.seconds << ", "
					          << h.self[2].horizon.seconds << " s (start 1 nm, 1 um, 1 mm off; "
					          << cpu_now() - t0 << " s CPU)\n";
				horizons.push_back(std::move(h));
			}
		}
		for (const Plugin &plugin : plugins) {
			std::vector<std::string> unexpressed;
			if (unsupported_models(*scenario, plugin, &unexpressed) && !unexpressed.empty()) {
				std::string list;
				for (const std::string &m : unexpressed)
					list += (list.empty() ? "" : ", ") + m;
				std::cerr << "pool-compare: warning: " << scenario->name << ": " << plugin.api->name
				          << " cannot express " << list << " (it runs its own laws; its errors include the "
				          << "difference: unsupported_models in results.json)\n";
			}
			std::vector<double> dts = o.dts;
			if (plugin.api->event_driven)
				dts.resize(1);
			for (double dt : dts) {
				RunSettings settings;
				settings.dt = dt;
				settings.min_repetitions = o.repeat;
				// The perturbed runs of the default sweep stop at 1e-4: at 1e-5 they would cost
				// 8 x 14 s of CPU for the break alone.
				const bool spread = plugin.api->event_driven || o.dts_given || dt >= 1e-4;
				settings.spread_runs = many_balls && spread && scenario->family.empty() ? o.spread : 0;
				settings.horizon_times = track_times;
				Record rec;
				const std::string title = scenario->name + " / " + plugin.api->name + " / " +
				                          (plugin.api->event_driven ? std::string("event") : "dt " + fmt_dt(dt));
				const Record blank = blank_record(*scenario, *ref, plugin, settings);
				auto run = [&] { return run_engine(*scenario, *ref, plugin, settings); };
				double cpu = kNone;
				const int lines = engine_log.capture(title, [&] {
					if (o.in_process) {
						const double t0 = cpu_now(), w0 = wall_now();
						rec = run();
						cpu = cpu_now() - t0;
						rec.wall_seconds = wall_now() - w0;
						rec.outcome = rec.error.empty() ? "ok" : "failed";
					} else {
						rec = run_isolated(run, blank, o.timeout, &cpu);
					}
				});
				rec.engine_messages = lines;
				if (!o.quiet)
					std::cerr << "  " << title << ": " << (rec.error.empty() ? "done" : rec.error) << " ("
					          << cpu << " s CPU, " << rec.wall_seconds << " s wall"
					          << (lines ? ", " + std::to_string(lines) + " engine messages in engines.log" : "")
					          << ")\n";
				if (publisher && !publisher->publish(rec, &error)) {
					std::cerr << "pool-compare: " << error << "\n";
					status = 1;
				}
				records.push_back(std::move(rec));
				save({});
			}
		}
	}

	if (!save({}))
		return 1;
	std::cout << results_table(records, false) << "\n" << accuracy_summary(records, 1e-3, false);
	const std::string flights = landing_table(records, false);
	if (!flights.empty())
		std::cout << "\n" << flights;
	const std::string links = link_table(records, false);
	if (!links.empty())
		std::cout << "\n" << links;
	const std::string chaos = horizon_table(records, horizons, false);
	if (!chaos.empty())
		std::cout << "\n" << chaos;
	for (double perturbation : {1e-3, 1e-6}) {
		const std::string scale = scale_table(records, horizons, perturbation, false);
		if (!scale.empty())
			std::cout << "\n" << scale;
	}
	const std::vector<std::string> plots = o.plots ? draw_plots(o) : std::vector<std::string>();
	if (!save(plots))
		return 1;
	if (!o.quiet)
		std::cerr << "pool-compare: wrote " << o.out << "/results.json, results.csv, report.md and " << plots.size()
		          << " plots\n";
	int failed = 0;
	for (const Record &r : records)
		failed += !r.error.empty();
	if (failed) {
		std::cerr << "pool-compare: " << failed << " of " << records.size()
		          << " runs failed (error rows in results.json, results.csv and report.md):\n";
		for (const Record &r : records)
			if (!r.error.empty())
				std::cerr << "  " << r.scenario << " / " << r.engine << " / "
				          << (r.event_driven ? std::string("event") : "dt " + fmt_dt(r.dt)) << ": " << r.error << "\n";
		status = 1;
	}
	return status;
}
