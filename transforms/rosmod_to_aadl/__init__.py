"""ROSMOD projects (``rosmod.ecore``) → declarative AADL (``aadl.ecore``), with a trace.

:func:`rosmod_to_aadl` applies the rules of :data:`TRANSFORMATION` (the rule engine of
:mod:`rosaadl.transforms.engine`) to a ``rosmod.Project`` and returns an ``AadlModel`` holding
the generated packages; they use the library's ``ros`` package and property sets (read them
with ``read_files(..., include_library=True)``). The mapping (``docs/rosmod-aadl-mapping.md``):

* **software** — one AADL package per ROSMOD package (``Unit_Kind => Software``): a message is
  a ``data`` type with ``ROS_Properties::Message_Type``, its ``.msg`` text
  (``ROSMOD_Properties::Definition``) and ``Data_Size`` when every message of the type has the
  same size; a service is a ``subprogram`` with an ``in parameter`` request and an ``out
  parameter`` response, both ``data`` types; a component is a ``thread group`` type (its ports as
  features: publisher → ``out event data port``, subscriber → ``in event data port``, client →
  ``requires subprogram access``, server → ``provides subprogram access``) and implementation
  holding one ``thread`` per timer (periodic, ``Period``/``Deadline``/``Priority``) and per
  subscriber or server callback (sporadic, ``Deadline``/``Priority``); the callback threads of a
  component share its callback queue (a ``data`` subcomponent of ``ros::callback_queue``, whose
  ``Concurrency_Control_Protocol`` makes them mutually exclusive: one executor per component
  instance). Message types of packages outside the project (``std_msgs/String``) become data
  types of an ``Interfaces`` package named after their ROS package;
* **hardware** — one package per hardware model (``Unit_Kind => Hardware``) with a ``system``
  implementation holding one ``processor`` per host (IP address, user, ssh key, paths,
  ``Hardware_Properties::Architecture``, OS), one ``bus`` per network and one ``bus access``
  connection per link;
* **deployment** — one package per deployment (``Unit_Kind => Deployment``) with one ``process``
  per node (extending ``ros::node``, ``Priority``, the component instances as thread group
  subcomponents) and a ``system`` implementation (the root to instantiate) holding the
  hardware, a ``ros::ROSbus`` virtual bus and the processes, bound with
  ``Actual_Processor_Binding``; topics (a publisher and a subscriber of the same message type,
  and for WebGME ports the same advertised topic) are port connections, bound with
  ``Actual_Connection_Binding`` to the network both hosts are linked to, else to the ROS bus;
  a client is connected to the first server of its service type;
* ROSMOD facts without an AADL counterpart go into ``ROSMOD_Properties`` (IP addresses, users,
  logging, port instances, settings, the project's own data in a ``Project`` package), so that
  :func:`rosaadl.transforms.aadl_to_rosmod.aadl_to_rosmod` gives the project back.

Names: a ROSMOD name that is not an AADL identifier, is a reserved word or repeats another
name of the same AADL namespace (AADL names are case-insensitive) gets a unique identifier
(:class:`NameScope`) and keeps its ROSMOD name in ``ROSMOD_Properties::Name``. Times in seconds
become integer AADL times in ``ms`` or ``us`` (``ns``, ``ps`` when needed), exactly.

The modules, one idea each: :mod:`.vocabulary` (the property and library names written),
:mod:`.names` (identifiers and namespaces), :mod:`.values` (times and set values),
:mod:`.factory` (making AADL objects), :mod:`.plan` (every name chosen before the rules run),
:mod:`.rules` (the transformation and what its rules share), the rules of :mod:`.project_unit`,
:mod:`.software`, :mod:`.hardware` and :mod:`.deployment`, :mod:`.topics` (connections of a
deployment), :mod:`.interfaces` (packages for types outside the project) and :mod:`.conversion`
(the entry point). They read and write no files.
"""

from rosaadl.transforms.rosmod_to_aadl import vocabulary
from rosaadl.transforms.rosmod_to_aadl.conversion import ConversionResult, rosmod_to_aadl
from rosaadl.transforms.rosmod_to_aadl.names import RESERVED_WORDS, NameScope, aadl_identifier
from rosaadl.transforms.rosmod_to_aadl.rules import TRANSFORMATION
from rosaadl.transforms.rosmod_to_aadl.values import given, plain_seconds, seconds_to_time, time_to_seconds
from rosaadl.transforms.rosmod_to_aadl.vocabulary import *  # noqa: F403 - the names the mapping writes

__all__ = [
    "ConversionResult",
    "rosmod_to_aadl",
    "NameScope",
    "aadl_identifier",
    "given",
    "seconds_to_time",
    "time_to_seconds",
    "plain_seconds",
    "RESERVED_WORDS",
    "TRANSFORMATION",
    *vocabulary.__all__,
]
