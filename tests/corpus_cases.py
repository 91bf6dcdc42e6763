"""The real-world corpus cases several test modules run over (one list, kept in one place).

Test modules import it as ``corpus_cases`` (the ``tests`` folder is on pytest's import path).
"""

from __future__ import annotations

#: folders of ``osate/aaxl2/`` holding an OSATE instance file (21)
OSATE_INSTANCE_DIRS = (
    "case-hamr-edp-domains",
    "ex-carsystem",
    "ex-crossdomain-security",
    "ex-issue228-featuregroups",
    "ex-issue440-arinc653",
    "ex-large-modes",
    "ex-latency-nobus",
    "ex-latency-normal",
    "ex-latency-partitioned-distributed",
    "ex-latency-unbound",
    "ex-mission-aircraft",
    "ex-pullprotocols",
    "ex-simple-thread-latency",
    "fmw-uav-v3",
    "gtse-atsv-tier0",
    "inspecta-firewall-platform",
    "osate2-emv2-annex-instance",
    "osate2-issue2318-bidir",
    "osate2-issue2780-featuregroups",
    "osate2-pulseox",
    "osate2-simple-control-modes",
)

#: folders of ``osate/aaxl2/`` holding a declarative ``.aaxl2`` (a package or a property set)
OSATE_DECLARATIVE_DIRS = (
    "ex-issue168-declarative-package",
    "ex-issue411-declarative-propertyset",
    "smaccm-geofence-declarative",
)

#: ROSMOD projects of ``rosmod/`` (textual v0.1–v0.4 and the AGSE robot), as folders or files
ROSMOD_PROJECTS = (
    "textual-v0.3/agse",
    "textual-v0.3/client-server",
    "textual-v0.3/integration",
    "textual-v0.3/isorc2016",
    "textual-v0.3/ksp_rover_controller",
    "textual-v0.3/long-running-operation",
    "textual-v0.3/periodic-timers",
    "textual-v0.3/publish-subscribe",
    "textual-v0.3/sequential-leds",
    "textual-v0.3/ten-components",
    "textual-v0.3/three-components",
    "textual-v0.3/timer",
    "textual-v0.3/timer_example",
    "textual-v0.3/trajectory-planner",
    "textual-v0.3/uav",
    "textual-v0.3/roscpp/ksp_rover_control",
    "textual-v0.3/roscpp/ksp_stearwing_control",
    "textual-v0.3/roscpp/pub_sub_cycle_example",
    "textual-v0.3/roscpp/pub_sub_traffic_gen",
    "textual-v0.3/roscpp/routing",
    "textual-v0.3/roscpp/tg_test",
    "legacy-v0.2/sample",
    "legacy-v0.1/input.rosml",
    "agse2015/agse_rosmod_project",
    "agse2015/agse_rosmod_v3",
)

#: WebGME seeds of ``rosmod/webgme/`` holding projects
WEBGME_SEEDS = ("samples-2016-06-13_noTLC.webgmex", "samples-2018-05-19_noTLC.webgmex")
