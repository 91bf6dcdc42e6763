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
