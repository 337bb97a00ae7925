// The text `bkquake --help` prints: every command with its synopsis. Kept apart from main()
// so that `bkquake readme-tables` copies the same text into docs/reference/commands.md.
#include "cli/commands.hpp"

namespace bkq {

const char* usage_text() {
  return R"(bkquake: earthquake statistics for Burridge-Knopoff spring-block chains and the BK-Pad model

Usage:
  bkquake run [SCENE] [--set section.key=value]... [--out DIR] [--resume] [--force]
  bkquake run --dump-defaults      print a commented scene with every key at its default
  bkquake fit CATALOG|HISTOGRAM|RUN_DIR|MERGED_DIR|SWEEP_DIR [--mu-min A] [--mu-max B] [--scan]
              [--measure moment|blocks|topplings|area|duration]
              [--bin-width W] [--blocks N] [--json OUT]
  bkquake merge RUN_DIR... --out DIR [--mu-min A] [--mu-max B] [--force]
  bkquake accuracy [SCENE] [--set section.key=value]... [--out DIR]
  bkquake spectrum RUN_DIR [--signal S] [--segment K | --from T0 --to T1] [--out FILE]
  bkquake special-speed [SCENE] [--set section.key=value]...
  bkquake special-law BK_RUN_DIR... > law.csv
  bkquake sweep SWEEP.ini [--set section.key=value]... --out DIR [--resume] [--force]
  bkquake friction-study [--out DIR] [--seeds N] [--jobs J] [--segment T]
  bkquake stability [SCENE] [--set section.key=value]... [--sweep KEY=FROM:TO:COUNT] [--out DIR] [--force]
  bkquake seismicity RUN_DIR|CATALOG [--out DIR] [--mainshock-mu X] [--blocks N] [--export FILE]
  bkquake --help | --version

Commands:
  run     simulate a scene (event-driven or continuously driven) and write
          scene.ini, catalog.csv, histogram.csv, summary.json (+ timeseries.csv)
  fit     fit the Gutenberg-Richter law R = A exp(-b mu) to an event catalogue
          (--measure: also a power law x^-tau of another size of the events)
  merge   merge the histograms of runs of the same scene and fit the result
  accuracy  work-precision study: error against time per event for every scheme and dt
  spectrum  amplitude spectrum of a continuous run's signal, peaks beside the natural
            frequencies (Ferre 2018 §4.3)
  special-speed  t_death and v_special = F0/(k_p t_death) of Ferre 2018 eq. 4.8
  special-law    the friction a held pad feels in BK runs, as a table (Ferre 2018 Fig. 4.8)
  sweep   run every point of a sweep file (also under mpirun) and write sweep.csv
  friction-study the four configurations of Ferre 2018 Fig. 4.6 over the speed grid
  stability  steady sliding and the complex eigenvalues of its linearisation (stability.csv)
  seismicity waiting times, recurrence, Omori-Utsu and Båth, moment rate, rupture scaling
            and the Mogi picture of a catalogue (RUN_DIR/seismicity/)

Examples:
  bkquake run                                    the Carlson-Langer reference, event-driven
  bkquake run data/scenes/thesis.ini --out runs/thesis
  bkquake run data/scenes/carlson-langer.ini --set friction.alpha=1 --set run.events=20000

Each command takes --help. Every scene key, its default, range and meaning:
'bkquake run --dump-defaults' and the documentation, docs/reference/scenes.md.
)";
}

const std::vector<CommandEntry>& listed_commands() {
  static const std::vector<CommandEntry> commands = {
      {"run", cmd_run},
      {"fit", cmd_fit},
      {"merge", cmd_merge},
      {"accuracy", cmd_accuracy},
      {"spectrum", cmd_spectrum},
      {"special-speed", cmd_special_speed},
      {"special-law", cmd_special_law},
      {"sweep", cmd_sweep},
      {"friction-study", cmd_friction_study},
      {"stability", cmd_stability},
      {"seismicity", cmd_seismicity},
  };
  return commands;
}

}  // namespace bkq
