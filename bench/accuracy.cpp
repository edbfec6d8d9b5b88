// cyclone-accuracy: the error of the simulation against what it costs. Reference scenes
// with a closed form or a converged reference are run at a sweep of step sizes, solver
// settings and integrators; each run is timed and its error measured. Writes a CSV, a
// Markdown report and one gnuplot script per scene and measure (scripts/accuracy.sh runs
// them and keeps the outputs in docs/accuracy/).
//
//   cyclone-accuracy --out DIR --plots DIR [--quick]
//
// Every scene is deterministic; only the CPU times vary from machine to machine.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "accuracy.h"
#include "accuracy_report.h"

namespace cyclone::accuracy {

std::string number(double v, int digits) {
    if (v >= kDiverged) return "diverged";
    std::ostringstream out;
    out.precision(digits);
    out << v;
    return out.str();
}

namespace {

std::string configLabel(const Config &c, bool withSolver) {
    std::string label = integratorName(c) + ", " + std::to_string(c.substeps) + " sub-step" + (c.substeps > 1 ? "s" : "");
    if (withSolver) label += " x " + std::to_string(c.iterations) + " it";
    return label;
}

bool contactScene(const std::string &scene) {
    for (const char *name : {"sliding-box", "rolling-sphere", "bouncing-ball", "resting-pyramid", "drops", "chain-20",
                             "chain-20-heavy", "chain-20-heavy-swing", "pendulum", "rolling-resistance"})
        if (scene == name) return true;
    return false;
}

void writeCsv(const std::string &path, const std::vector<Row> &rows) {
    std::ofstream out(path);
    out << "scene,measure,integrator,dt,iterations,substeps,parameter,cpu_ms_per_simulated_s,error\n";
    out.precision(9);
    for (const Row &r : rows)
        out << r.scene << ",\"" << r.measure << "\"," << integratorName(r.config) << "," << r.config.dt << ","
            << r.config.iterations << "," << r.config.substeps << ",\"" << r.config.parameter << "\","
            << r.cpuMsPerSimSecond << "," << r.error << "\n";
}

// A configuration's look, the same in every plot: a colour per scheme and sub-step count
// (a strong shade for 4 sub-steps, a lighter, dashed one for 1), open points for 10
// iterations.
std::string lineStyle(const Config &c) {
    static const std::map<std::string, std::pair<const char *, const char *>> colours = {
        {"newton-euler", {"#1f4e9c", "#6fa8dc"}},
        {"newton-euler (no speculative contacts)", {"#795548", "#bcaaa4"}},
        {"newton-euler (explicit springs)", {"#7f7f7f", "#b0b0b0"}},
        {"newton-euler-gyroscopic", {"#b8860b", "#e6b800"}},
        {"newton-euler-implicit", {"#2e7d32", "#81c784"}},
        {"momentum-conserving", {"#c62828", "#ef7f7f"}},
        {"rigidbody-backward-euler", {"#6a1b9a", "#b39ddb"}},
        {"splitting (bench only)", {"#00838f", "#80deea"}},
    };
    const auto found = colours.find(integratorName(c));
    const auto shades = found != colours.end() ? found->second : std::make_pair("#000000", "#555555");
    const bool one = c.substeps == 1;
    std::string style = std::string("lc rgb '") + (one ? shades.second : shades.first) + "' lw 2 dt " +
                        (one ? "2" : "1") + " pt " + (c.iterations > 3 ? "6" : "7") + " ps 0.8";
    return style;
}

// One gnuplot script per scene and measure: error against CPU time, log-log, one line per
// configuration through its step sizes.
std::string writePlot(const std::string &plotsDir, const std::string &outDir, const std::string &scene,
                      const std::string &key, const std::string &measure, const std::vector<const Row *> &rows) {
    const std::string name = scene + "-" + key;
    std::map<std::string, std::vector<const Row *>> series;
    std::vector<std::string> order;
    std::map<std::string, std::string> styles;
    for (const Row *r : rows) {
        const std::string label = configLabel(r->config, contactScene(scene));
        if (!series.count(label)) order.push_back(label);
        series[label].push_back(r);
        styles[label] = lineStyle(r->config);
    }
    // An error of exactly 0 (a landing with no penetration at all) has no place on a log
    // axis: it is drawn at kZeroDrawnAt, below every error measured, and the title says so.
    constexpr double kZeroDrawnAt = 1e-10;
    bool zeros = false;
    std::ofstream data(plotsDir + "/" + name + ".dat");
    data.precision(9);
    for (const std::string &label : order) {
        data << "# " << label << "\n";
        for (const Row *r : series[label]) {
            if (r->error >= kDiverged || !(r->error >= 0)) continue;
            zeros = zeros || r->error == 0;
            const std::string label = r->config.parameter.empty() ? fraction(r->config.dt) : r->config.parameter;
            data << r->cpuMsPerSimSecond << " " << (r->error > 0 ? r->error : kZeroDrawnAt) << " \"" << label
                 << "\"\n";
        }
        data << "\n\n";
    }
    std::ofstream gp(plotsDir + "/" + name + ".gp");
    // Legend below the plot, outside it, so it never covers a line.
    const int legendRows = static_cast<int>((order.size() + 1) / 2);
    gp << "set terminal svg size 900," << 560 + 22 * legendRows << " dynamic font 'sans,12' background rgb 'white'\n"
       << "set output '" << outDir << "/" << name << ".svg'\n"
       << "set title \"" << scene << ": " << measure << (zeros ? "\\n(an error of exactly 0 is drawn at 1e-10)" : "")
       << "\"\n"
       << "set xlabel 'CPU time per simulated second (ms)'\n"
       << "set ylabel \"" << measure << "\"\n"
       << "set logscale xy\nset format y '10^{%L}'\nset grid\nset key outside below left maxcols 2 noenhanced\n"
       << (zeros ? "set yrange [3e-11:*]\n" : "")
       << "plot ";
    for (std::size_t i = 0; i < order.size(); ++i) {
        if (i) gp << ", \\\n     ";
        gp << "'" << plotsDir << "/" << name << ".dat' index " << i << " using 1:2 with linespoints "
           << styles[order[i]] << " title \"" << order[i] << "\"";
        if (i == 0) gp << ", '' index 0 using 1:2:3 with labels offset 1.2,0.6 font ',8' notitle";
    }
    gp << "\n";
    return name + ".svg";
}

void writeMarkdown(const std::string &path, const std::vector<Scene> &all, const std::vector<Row> &rows,
                   const std::map<std::string, std::vector<std::string>> &plots, double seconds, bool quick) {
    std::ofstream md(path);
    md << "# Accuracy against cost\n\n"
       << "Generated by `bash scripts/accuracy.sh` (bench/accuracy.cpp" << (quick ? ", --quick" : "")
       << "); every number below is measured, the CPU times on the machine that ran it. The whole sweep took "
       << number(seconds, 3) << " s. Full data: [results.csv](results.csv).\n\n"
       << "Each scene runs at step sizes from 1/15 s to 1/960 s (the hanging chains at three of them) and the "
       << "solver settings shown; \"it\" is "
       << "velocity iterations per sub-step. Errors are against the closed form or converged reference "
       << "named. Cost is the CPU time of the stepping per simulated second (ms), read from the process's CPU "
       << "clock so that other programs on a shared machine do not inflate it, the least of up to five "
       << "identical runs when a run is short. In the plots each configuration has one colour "
       << "throughout: a strong shade for 4 sub-steps, a lighter dashed one for 1, open points for 10 "
       << "iterations.\n";
    writeSummary(md, rows);
    for (const Scene &scene : all) {
        md << "\n## " << scene.name << "\n\n" << scene.description << ".\n";
        std::vector<std::string> measures;
        for (const Row &r : rows)
            if (r.scene == scene.name && std::find(measures.begin(), measures.end(), r.measure) == measures.end())
                measures.push_back(r.measure);
        for (const std::string &measure : measures) {
            md << "\n### " << measure << "\n\n";
            const auto found = plots.find(scene.name + "|" + measure);
            if (found != plots.end())
                md << "![" << scene.name << ": " << measure << "](" << found->second[0] << ")\n\n";
            else
                md << "Exactly 0 in every run below (nothing to plot on a log scale).\n\n";
            // Pivot: one line per configuration, one column per step size; cells "error (ms/s)".
            std::vector<double> dts;
            std::vector<std::string> labels;
            std::map<std::string, std::map<double, const Row *>> cells;
            for (const Row &r : rows) {
                if (r.scene != scene.name || r.measure != measure) continue;
                const std::string label = configLabel(r.config, contactScene(scene.name));
                if (std::find(labels.begin(), labels.end(), label) == labels.end()) labels.push_back(label);
                if (std::find(dts.begin(), dts.end(), r.config.dt) == dts.end()) dts.push_back(r.config.dt);
                cells[label][r.config.dt] = &r;
            }
            std::sort(dts.begin(), dts.end(), std::greater<>());
            md << "| configuration |";
            for (double dt : dts) {
                md << " " << fraction(dt);
                if (scene.name == "stiff-spring") md << " (ωdt " << number(kSpringOmega * dt, 2) << ")";
                md << " |";
            }
            md << "\n|---|";
            for (std::size_t i = 0; i < dts.size(); ++i) md << "--:|";
            md << "\n";
            for (const std::string &label : labels) {
                md << "| " << label << " |";
                for (double dt : dts) {
                    const auto cell = cells[label].find(dt);
                    if (cell == cells[label].end()) {
                        md << " |";
                        continue;
                    }
                    md << " " << number(cell->second->error) << " <sub>(" << number(cell->second->cpuMsPerSimSecond, 2)
                       << " ms)</sub> |";
                }
                md << "\n";
            }
        }
    }
}

int run(int argc, char **argv) {
    std::string outDir = "docs/accuracy", plotsDir = ".";
    bool quick = false;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--out" && i + 1 < argc) outDir = argv[++i];
        else if (arg == "--plots" && i + 1 < argc) plotsDir = argv[++i];
        else if (arg == "--quick") quick = true;
        else {
            std::cerr << "usage: cyclone-accuracy [--out DIR] [--plots DIR] [--quick]\n"
                         "  --out DIR    results.csv, README.md and (through the scripts) the plots; default docs/accuracy\n"
                         "  --plots DIR  gnuplot data and scripts, one per scene and measure; default .\n"
                         "  --quick      three step sizes instead of seven\n";
            return 2;
        }
    }
    const auto start = std::chrono::steady_clock::now();
    std::vector<Scene> all;
    addMotionScenes(all, quick);
    addContactScenes(all, quick);
    std::vector<Row> rows;
    for (const Scene &scene : all) {
        const auto t0 = std::chrono::steady_clock::now();
        for (const Config &c : scene.configs) {
            // Runs are deterministic: repeating a short one and keeping its fastest time
            // only removes interference from the rest of the machine.
            Outcome o = scene.run(c);
            for (int repeat = 1; repeat < 5 && o.cpuSeconds < 0.05; ++repeat)
                o.cpuSeconds = std::min(o.cpuSeconds, scene.run(c).cpuSeconds);
            for (const Measure &m : o.measures)
                rows.push_back({scene.name, m.key, m.name, c, 1000 * o.cpuSeconds / o.simulatedSeconds, m.value});
        }
        std::cerr << scene.name << ": " << scene.configs.size() << " runs, "
                  << std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() << " s\n";
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    std::map<std::string, std::vector<std::string>> plots;
    for (const Scene &scene : all) {
        std::map<std::string, std::vector<const Row *>> byMeasure;
        std::vector<std::string> measures;
        for (const Row &r : rows) {
            if (r.scene != scene.name) continue;
            if (!byMeasure.count(r.measure)) measures.push_back(r.measure);
            byMeasure[r.measure].push_back(&r);
        }
        for (const std::string &m : measures) {
            const auto &measured = byMeasure[m];
            // Nothing to plot when every run is exact (the report says so instead).
            if (std::all_of(measured.begin(), measured.end(), [](const Row *r) { return r->error == 0; })) continue;
            plots[scene.name + "|" + m].push_back(
                writePlot(plotsDir, outDir, scene.name, byMeasure[m].front()->key, m, byMeasure[m]));
        }
    }
    writeCsv(outDir + "/results.csv", rows);
    writeMarkdown(outDir + "/README.md", all, rows, plots, seconds, quick);
    std::cerr << rows.size() << " results in " << seconds << " s: " << outDir << "/results.csv, " << outDir
              << "/README.md\n";
    return 0;
}

}  // namespace
}  // namespace cyclone::accuracy

int main(int argc, char **argv) { return cyclone::accuracy::run(argc, argv); }