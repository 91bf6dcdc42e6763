"""OSATE ``.aaxl2`` instance files generated at scale (``bench_aaxl2``, ``bench_aaxl2_export``).

:func:`write_aaxl2_instance` writes a current-era instance file as OSATE writes them: processors,
processes bound to them, periodic threads with their properties, chained by port connections.
"""

from __future__ import annotations

import io
import os
from pathlib import Path

__all__ = ["write_aaxl2_instance"]

_HEADER = (
    '<?xml version="1.0" encoding="ASCII"?>\n'
    '<instance:SystemInstance xmi:version="2.0" xmlns:xmi="http://www.omg.org/XMI" '
    'xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance" xmlns:aadl2="http://aadl.info/AADL/2.0" '
    'xmlns:instance="http://aadl.info/AADL/2.0/instance" name="gen_impl_Instance" category="system">\n'
)
_PS = "platform:/plugin/org.osate.aadl2.contrib/resources/properties/Predeclared_Property_Sets/"
_AADL = "../gen.aadl#/0/@ownedPublicSection/@ownedClassifier."


def _pa(prop: str, value: str, indent: str) -> str:
    return (
        f'{indent}<ownedPropertyAssociation xsi:type="instance:PropertyAssociationInstance">\n'
        f'{indent}  <property href="{_PS}{prop}"/>\n'
        f"{indent}  <ownedValue>\n{value}{indent}  </ownedValue>\n"
        f"{indent}</ownedPropertyAssociation>\n"
    )


def _integer(value: int, unit: str, indent: str, tag: str = "ownedValue") -> str:
    return (
        f'{indent}<{tag} xsi:type="aadl2:IntegerLiteral" value="{value}">\n'
        f'{indent}  <unit href="{_PS}AADL_Project.aadl#/0/@ownedPropertyType.{unit}"/>\n'
        f"{indent}</{tag}>\n"
    )


_MS = "16/@ownedLiteral.3"
_BYTES = "15/@ownedLiteral.1"
# objects our importer makes per thread (component, 2 features, 5 property associations with
# their values, 1 connection with 2 references) and per process / processor.
_PER_THREAD = 1 + 2 + (3 + 3 + 5 + 4) + 3 + 3
_PER_PROCESS = 1 + 4
_PER_PROCESSOR = 1


def write_aaxl2_instance(
    path: str | os.PathLike[str], objects: int = 50_000, threads_per_process: int = 50
) -> int:
    """Write a realistic current-era instance file with about ``objects`` objects; return the count
    of the objects our importer makes of it.

    Processors, processes bound to them and periodic threads with Period, Dispatch_Protocol,
    Compute_Execution_Time, Actual_Processor_Binding and Data_Size, chained by port connections.
    """
    per_process = _PER_PROCESS + threads_per_process * _PER_THREAD + _PER_PROCESSOR
    processes = max(1, (objects - 3) // per_process)
    out = io.StringIO()
    out.write(_HEADER)
    for p in range(processes):
        out.write(f'  <componentInstance name="cpu{p}" category="processor">\n')
        out.write(
            '    <subcomponent xsi:type="aadl2:ProcessorSubcomponent" '
            f'href="{_AADL}9/@ownedProcessorSubcomponent.{p}"/>\n'
        )
        out.write("    <index>0</index>\n")
        out.write('    <classifier xsi:type="aadl2:ProcessorType" href="../gen.aadl#gen.cpu"/>\n')
        out.write("  </componentInstance>\n")
    for p in range(processes):
        cpu = f"//@componentInstance.{p}"
        out.write(f'  <componentInstance name="proc{p}" category="process">\n')
        binding = (
            '        <ownedValue xsi:type="aadl2:ListValue">\n'
            '          <ownedListElement xsi:type="instance:InstanceReferenceValue" '
            f'referencedInstanceObject="{cpu}"/>\n'
            "        </ownedValue>\n"
        )
        out.write(
            _pa("Deployment_Properties.aadl#Deployment_Properties.Actual_Processor_Binding", binding, "    ")
        )
        for t in range(threads_per_process):
            out.write(f'    <componentInstance name="t{t}" category="thread">\n')
            ind = "      "
            out.write(
                _pa(
                    "Timing_Properties.aadl#Timing_Properties.Period",
                    _integer(10 * (t + 1), _MS, ind + "    "),
                    ind,
                )
            )
            dispatch = (
                f'{ind}    <ownedValue xsi:type="aadl2:NamedValue">\n'
                f'{ind}      <namedValue xsi:type="aadl2:EnumerationLiteral" '
                f'href="{_PS}AADL_Project.aadl#/0/@ownedPropertyType.3/@ownedLiteral.0"/>\n'
                f"{ind}    </ownedValue>\n"
            )
            out.write(_pa("Thread_Properties.aadl#Thread_Properties.Dispatch_Protocol", dispatch, ind))
            cet = (
                f'{ind}    <ownedValue xsi:type="aadl2:RangeValue">\n'
                + _integer(1, _MS, ind + "      ", "minimum")
                + _integer(t % 7 + 2, _MS, ind + "      ", "maximum")
                + f"{ind}    </ownedValue>\n"
            )
            out.write(_pa("Timing_Properties.aadl#Timing_Properties.Compute_Execution_Time", cet, ind))
            out.write(
                _pa(
                    "Deployment_Properties.aadl#Deployment_Properties.Actual_Processor_Binding",
                    binding.replace("        ", ind + "    "),
                    ind,
                )
            )
            out.write(f'{ind}<featureInstance name="inp" category="eventDataPort">\n')
            out.write(
                f'{ind}  <feature xsi:type="aadl2:EventDataPort" href="{_AADL}1/@ownedEventDataPort.0"/>\n'
            )
            out.write(f"{ind}</featureInstance>\n")
            out.write(f'{ind}<featureInstance name="outp" category="eventDataPort" direction="out">\n')
            out.write(
                _pa(
                    "Memory_Properties.aadl#Memory_Properties.Data_Size",
                    _integer(64 * (t + 1), _BYTES, ind + "      "),
                    ind + "  ",
                )
            )
            out.write(
                f'{ind}  <feature xsi:type="aadl2:EventDataPort" href="{_AADL}1/@ownedEventDataPort.1"/>\n'
            )
            out.write(f"{ind}</featureInstance>\n")
            out.write(
                f'{ind}<subcomponent xsi:type="aadl2:ThreadSubcomponent" '
                f'href="{_AADL}3/@ownedThreadSubcomponent.{t}"/>\n'
            )
            out.write(f"{ind}<index>0</index>\n")
            out.write(
                f'{ind}<classifier xsi:type="aadl2:ThreadImplementation" '
                'href="../gen.aadl#gen.worker.impl"/>\n'
            )
            out.write("    </componentInstance>\n")
        for t in range(threads_per_process):
            src = f"//@componentInstance.{processes + p}/@componentInstance.{t}/@featureInstance.1"
            dst_t = (t + 1) % threads_per_process
            dst = f"//@componentInstance.{processes + p}/@componentInstance.{dst_t}/@featureInstance.0"
            out.write(
                f'    <connectionInstance name="t{t}.outp -> t{dst_t}.inp" '
                'complete="true" kind="portConnection" '
                f'destination="{dst}" source="{src}">\n'
            )
            for _ in range(2):
                out.write(
                    f'      <connectionReference context="//@componentInstance.{processes + p}" '
                    f'source="{src}" destination="{dst}">\n'
                    '        <connection xsi:type="aadl2:PortConnection" '
                    f'href="{_AADL}3/@ownedPortConnection.{t}"/>\n'
                    "      </connectionReference>\n"
                )
            out.write("    </connectionInstance>\n")
        out.write(
            '    <subcomponent xsi:type="aadl2:ProcessSubcomponent" '
            f'href="{_AADL}5/@ownedProcessSubcomponent.{p}"/>\n'
        )
        out.write("    <index>0</index>\n")
        out.write(
            '    <classifier xsi:type="aadl2:ProcessImplementation" href="../gen.aadl#gen.app.impl"/>\n'
        )
        out.write("  </componentInstance>\n")
    out.write('  <systemOperationMode name="No Modes"/>\n')
    out.write(
        '  <componentImplementation xsi:type="aadl2:SystemImplementation" href="../gen.aadl#gen.top.impl"/>\n'
    )
    out.write("</instance:SystemInstance>\n")
    Path(path).write_text(out.getvalue(), encoding="ascii")
    # the AadlModel, the root, its operation mode, and what each process brings
    return 3 + processes * per_process
