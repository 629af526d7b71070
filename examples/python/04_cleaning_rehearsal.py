"""Example 04 (Python): a cleaning job rehearsed on the insulator cleaning robot's behaviour model.

robots/insulator_cleaner_behaviors.yaml (Wang et al. 2018): the robot climbs down a string of
3 discs, cleaning each (CB1 move down one disc, CB2 clean it), then climbs back up (CB3 per
disc). mcws.behave runs the job on the simulated robot, first clean, then with the faults of
scenarios/faults/rehearsal.yaml (a wrong and a corrupted command, a 12 s link outage, a stuck
zero switch the operator repairs after 45 s, a battery drain of 0.5 A). Checks: both runs end
back at the top with every disc cleaned, the clean one by the plan's 9 sub-tasks and commands
numbered 1..N, the faulted one with each fault's reaction timed as scripted.
Usage: python3 04_cleaning_rehearsal.py   (PYTHONPATH=build/python)
"""
import math
import os
import sys

import mcws

here = os.path.dirname(__file__)
robots = os.environ.get("MCWS_ROBOTS_DIR", os.path.join(here, "../../robots"))
scenarios = os.environ.get("MCWS_SCENARIOS_DIR", os.path.join(here, "../../scenarios"))
model = os.path.join(robots, "insulator_cleaner_behaviors.yaml")

clean = mcws.behave(model, 3)
faulted = mcws.behave(model, 3, os.path.join(scenarios, "faults", "rehearsal.yaml"))
for name, run in (("clean", clean), ("faulted", faulted)):
    print(f"{name}: {run.status}, {run.discs_cleaned} discs in {run.duration_s:.1f} s, "
          f"{run.commands_sent} commands, battery {run.battery_charge_used_Ah:.3f} Ah used")
for fault in faulted.faults:
    print(f"  {fault['fault']} at {fault['injected_t_s']} s: {fault['reaction']}")

done = all(run.status == "completed" and run.failure is None and run.discs_cleaned == 3
           and run.final_disc == 0 and run.invariant["holds"] for run in (clean, faulted))
plan = [step["cb"] for step in clean.plan] == ["CB1", "CB2"] * 3 + ["CB3"] * 3
seqs = [r["seq"] for r in clean.log if r["event"] == "command"]
numbered = seqs == list(range(1, clean.commands_sent + 1))
faults = {f["fault"]: f for f in faulted.faults}
link, stuck = faults.get("link_down", {}), faults.get("timeout", {})
timed = (sorted(faults) == ["corrupt_command", "link_down", "timeout", "wrong_command"]
         and math.isclose(link["resolved_t_s"] - link["injected_t_s"], 12)  # the outage
         and math.isclose(stuck["resolved_t_s"] - stuck["detected_t_s"], 45))  # the repair
# The faulted run does the whole clean job and more, with 0.5 A more drawn all along.
drained = (faulted.battery_charge_used_Ah
           >= clean.battery_charge_used_Ah + 0.5 * faulted.duration_s / 3600)
sys.exit(0 if done and plan and numbered and timed and drained else 1)
