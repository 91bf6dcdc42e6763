"""OSATE eras: how `.aaxl2` files point into the predeclared property sets, per OSATE version.

OSATE writes units and enumeration literals (and record fields) of property values as
*positional* references into the property set that declares them, for example
``…/AADL_Project.aadl#/0/@ownedPropertyType.16/@ownedLiteral.3`` (``Time_Units``, literal ``ms``).
The positions follow the declaration order of the property set OSATE shipped, which changed
between versions, and so did the URI under which the predeclared sets are found:

* ``2014``: ``../../Plugin_Resources/<Set>.aadl`` (relative, in the workspace); fragments
  ``//@…``;
* ``2017-2020``: ``…/org.osate.workspace/resources/properties/Predeclared_Property_Sets/<Set>.aadl``
  (``platform:/plugin/…``, or made relative by EMF); fragments ``/0/@…``;
* ``current``: ``…/org.osate.aadl2.contrib/resources/properties/Predeclared_Property_Sets/<Set>.aadl``;
  fragments ``/0/@…``.

The SEI-contributed sets (``SEI``, ``Data_Model``, ``ARINC653``, …) live under
``…/org.osate.contribution.sei/resources/properties/`` in both later eras, and the EMV2 sets
under ``…/org.osate.aadl2.errormodel.contrib/resources/properties/`` (current era only).

This module holds, per era and per property set, the facts needed to decode such references
and to write them again: which container (enumeration type, units type, record type) sits at
which position, the names of its literals or fields in order, the property definitions in
declaration order, and the units type each number-valued property or record field uses. The
tables are this project's own compact notation, one line per container:

``T<n>``  ``@ownedPropertyType.<n>`` (a declared property type)
``P<n>``  ``@ownedProperty.<n>/@ownedPropertyType`` (the anonymous type of a property)
``C<n>``  ``@ownedPropertyConstant.<n>/@ownedPropertyType``
``/F<k>`` ``/@ownedField.<k>/@ownedPropertyType`` (the anonymous type of a record field)
``/E`` ``/@ownedElementType`` (list element), ``/U`` ``/@ownedUnitsType``, ``/N`` ``/@ownedNumberType``

followed by the container kind (``enum``, ``units``, ``record``), its name (the type's name, or
the property's for an anonymous type, ``Record.Field`` for a field's type) and its literals or
fields. The ``props`` line lists the property definitions in order, ``Name:Set::Units_Type`` for
those whose values carry units. Literal *k* of a container is ``<container>/@ownedLiteral.<k>``,
field *k* is ``<container>/@ownedField.<k>``.

The snapshots behind the tables are OSATE's sets of September 2014, October 2017 and today.
OSATE shipped some contributed sets ahead of the predeclared ones (a 2014 file may already use
the 2017 layout of ``ARINC653``): :func:`choose_era` then decodes that set with the era whose
table fits. Known ambiguity: the literals of ``Data_Rate_Units`` were reordered inside the
current era (2023); a current-era file written before that decodes them with the newer order.
"""

from __future__ import annotations

import re
from collections.abc import Iterable
from dataclasses import dataclass, field
from functools import cache, lru_cache

from rosaadl.errors import UsageError

__all__ = [
    "ERAS",
    "CURRENT_ERA",
    "Literal",
    "PredeclaredUri",
    "HrefUse",
    "EraChoice",
    "EraTable",
    "table",
    "check_use",
    "fragment",
    "classify_uri",
    "normalize_fragment",
    "choose_era",
    "predeclared_uri",
]

#: The eras, oldest first.
ERAS: tuple[str, ...] = ("2014", "2017-2020", "current")
CURRENT_ERA = "current"

_BLOCKS: dict[str, str] = {
    "ARINC429@2014": """
props WordID FirstBit NumberBits""",
    "ARINC653@2014": """
props Partition_Slots:AADL_Project::Time_Units Slots_Allocation
  Module_Major_Frame:AADL_Project::Time_Units Sampling_Refresh_Period:AADL_Project::Time_Units
  HM_Errors HM_Module_Recovery_Actions Multipartitions HM_Multipartitions_Errors
  HM_Multipartitions_Recovery_Actions HM_Partition_Recovery_Actions HM_Process_Recovery_Actions
  HM_Callback Access_Type Memory_Type Timeout:AADL_Project::Time_Units Criticality
  System_Overhead_Time:AADL_Project::Time_Units Module_Version Module_Identifier Partition_Identifier
  Partition_Name System_Partition Partition_Stack Entrypoint Error_Handling
T0 enum Supported_Error_Code: Module_Config Module_Init Module_Scheduling Partition_Scheduling
  Partition_Config Partition_Handler Partition_Init Deadline_Miss Application_Error Numeric_Error
  Illegal_Request Stack_Overflow Memory_Violation Hardware_Fault Power_Fail
T1 enum Supported_Module_Recovery_Action: Ignore Stop Reset
T2 enum Supported_Partition_Recovery_Action: Ignore Partition_Stop Warm_Restart Cold_Restart
T3 enum Supported_Process_Recovery_Action: Ignore Confirm Partition_Stop Process_Stop
  Process_Stop_And_Start_Another Process_Restart Nothing Cold_Restart Warm_Restart
T4 enum Supported_Access_Type: read write execute
T5 enum Supported_Memory_Type: Data_Memory Code_Memory IO_Memory
T6 enum Supported_Criticality_Type: LEVEL_A LEVEL_B LEVEL_C LEVEL_D LEVEL_E""",
    "Data_Model@2014": """
props Base_Type Code_Set Data_Digits Data_Scale Data_Representation MyDimension Dimension
  Element_Names Enumerators IEEE754_Precision Initial_Value Integer_Range Measurement_Unit
  Number_Representation Real_Range Representation
P4 enum Data_Representation: Array Boolean Character Enum Float Fixed Integer String Struct Union
P9 enum IEEE754_Precision: Simple Double
P13 enum Number_Representation: Signed Unsigned""",
    "SEI@2014": """
props SecurityLevel SafetyCriticality StreamMissRate NetWeight:SEI::WeightUnits
  GrossWeight:SEI::WeightUnits WeightLimit:SEI::WeightUnits StateRepresentation ProtocolQoS
  Partition_Latency:AADL_Project::Time_Units Is_Partition
  InstructionsPerDispatch:SEI::InstructionVolumeUnits MIPSCapacity:SEI::Processor_Speed_Units
  MIPSBudget:SEI::Processor_Speed_Units RAMCapacity:AADL_Project::Size_Units
  RAMBudget:AADL_Project::Size_Units ROMCapacity:AADL_Project::Size_Units
  ROMBudget:AADL_Project::Size_Units PowerCapacity:SEI::Power_Units PowerBudget:SEI::Power_Units
  PowerSupply:SEI::Power_Units BandWidthCapacity:AADL_Project::Data_Rate_Units
  BandWidthBudget:AADL_Project::Data_Rate_Units RAMActual:AADL_Project::Size_Units
  ROMActual:AADL_Project::Size_Units Data_Rate:SEI::Data_Rate nsloc vdid_inspect Broadcast_Protocol
  Model_References
T0 units WeightUnits: kg
T1 enum StateRepresentationType: State StateDelta
T2 enum ProtocolQoSType: GuaranteedDelivery SecureDelivery OrderedDelivery
T3 units InstructionVolumeUnits: IPD KIPD MIPD
T4 units Processor_Speed_Units: KIPS MIPS GIPS
T5 units Power_Units: mW W KW
T6 enum Reference_Kind_Type: any exist component connection behavior unknown
T7 enum Model_Source_Type: simulink scade geometry_stp sysml
T8 record Model_Reference: Model_Type Kind Filename Artifact
P24/U units Data_Rate: perSecond""",
    "AADL_Project@2014": """
props
T0 enum Supported_Active_Thread_Handling_Protocols: abort
T1 enum Supported_Connection_Patterns: One_To_One All_To_All One_To_All All_To_One Next Previous
  Cyclic_Next Cyclic_Previous Odd_To_Odd Even_To_Even Next_Next Cyclic_Next_Next Previous_Previous
  Cyclic_Previous_Previous
T2 enum Supported_Concurrency_Control_Protocols: None_Specified Interrupt_Masking Maximum_Priority
  Priority_Inheritance Priority_Ceiling Spin_Lock Semaphore Protected_Access
T3 enum Supported_Dispatch_Protocols: Periodic Sporadic Aperiodic Timed Hybrid Background
T4 enum Supported_Queue_Processing_Protocols: Fifo
T5 enum Supported_Hardware_Source_Languages: VHDL
T6 enum Supported_Connection_QoS: GuaranteedDelivery OrderedDelivery SecureDelivery
T7 enum Supported_Scheduling_Protocols: Static Round_Robin_Protocol
  POSIX_1003_HIGHEST_PRIORITY_FIRST_PROTOCOL FixedTimeline Cooperative RMS EDF SporadicServer
  SlackServer ARINC653
T8 enum Supported_Source_Languages: Ada95 Ada2005 C Java Simulink_6_5
T9 enum Supported_Distributions: Fixed Poisson
T10 enum Supported_Classifier_Substitutions: Classifier_Match Type_Extension Signature_Match
T11 units Size_Units: bits Bytes KByte MByte GByte TByte
T12 units Time_Units: ps ns us ms sec min hr
T13 units Data_Rate_Units: bitsps Bytesps KBytesps MBytesps GBytesps
T14 units Data_Volume_Units: bitsps Bytesps KBytesps MBytesps GBytesps
T16 units Processor_Speed_Units: KIPS MIPS GIPS""",
    "Communication_Properties@2014": """
props Fan_Out_Policy Connection_Pattern Connection_Set Overflow_Handling_Protocol
  Queue_Processing_Protocol Queue_Size Required_Connection Timing Transmission_Type Input_Rate
  Input_Time Output_Rate Output_Time Subprogram_Call_Rate Transmission_Time
  Actual_Latency:AADL_Project::Time_Units Latency:AADL_Project::Time_Units
  Data_Rate:AADL_Project::Data_Rate_Units
T0 record Connection_Pair: src dst
T1 record IO_Time_Spec: Offset:AADL_Project::Time_Units Time
T2 enum IO_Reference_Time: Dispatch Start Completion Deadline NoIO
T3 record Rate_Spec: Value_Range Rate_Unit Rate_Distribution
T3/F1 enum Rate_Spec.Rate_Unit: PerSecond PerDispatch
P0 enum Fan_Out_Policy: Broadcast RoundRobin Selective OnDemand
P3 enum Overflow_Handling_Protocol: DropOldest DropNewest Error
P7 enum Timing: sampled immediate delayed
P8 enum Transmission_Type: push pull
P14 record Transmission_Time: Fixed:AADL_Project::Time_Units PerByte:AADL_Project::Time_Units""",
    "Deployment_Properties@2014": """
props Allowed_Processor_Binding_Class Allowed_Processor_Binding Actual_Processor_Binding
  Allowed_Memory_Binding_Class Allowed_Memory_Binding Actual_Memory_Binding
  Allowed_Connection_Binding_Class Allowed_Connection_Binding Actual_Connection_Binding
  Actual_Function_Binding Allowed_Subprogram_Call Actual_Subprogram_Call
  Allowed_Subprogram_Call_Binding Actual_Subprogram_Call_Binding Provided_Virtual_Bus_Class
  Required_Virtual_Bus_Class Provided_Connection_Quality_Of_Service
  Required_Connection_Quality_Of_Service Not_Collocated Collocated Allowed_Connection_Type
  Allowed_Dispatch_Protocol Allowed_Period:AADL_Project::Time_Units Allowed_Physical_Access_Class
  Allowed_Physical_Access Memory_Protocol Runtime_Protection_Support Scheduling_Protocol
  Preemptive_Scheduler Thread_Limit Priority_Map Priority_Range
T0 record Priority_Mapping: Aadl_Priority RTOS_Priority
P18 record Not_Collocated: Targets Location
P19 record Collocated: Targets Location
P20/E enum Allowed_Connection_Type: Sampled_Data_Connection Immediate_Data_Connection
  Delayed_Data_Connection Port_Connection Data_Access_Connection Subprogram_Access_Connection
P25 enum Memory_Protocol: execute_only read_only write_only read_write""",
    "Memory_Properties@2014": """
props Access_Right Access_Time Allowed_Message_Size:AADL_Project::Size_Units Assign_Time
  Base_Address Device_Register_Address Read_Time Source_Code_Size:AADL_Project::Size_Units
  Source_Data_Size:AADL_Project::Size_Units Source_Heap_Size:AADL_Project::Size_Units
  Source_Stack_Size:AADL_Project::Size_Units Byte_Count Memory_Size:AADL_Project::Size_Units
  Word_Size:AADL_Project::Size_Units Word_Space Write_Time
T2 enum Access_Rights: read_only write_only read_write by_method
P1 record Access_Time: First Last
P3 record Assign_Time: Fixed:AADL_Project::Time_Units PerByte:AADL_Project::Time_Units
P6 record Read_Time: Fixed:AADL_Project::Time_Units PerByte:AADL_Project::Time_Units
P15 record Write_Time: Fixed:AADL_Project::Time_Units PerByte:AADL_Project::Time_Units""",
    "Modeling_Properties@2014": """
props Acceptable_Array_Size:AADL_Project::Size_Units Classifier_Matching_Rule
  Classifier_Substitution_Rule Implemented_As Prototype_Substitution_Rule
P1 enum Classifier_Matching_Rule: Classifier_Match Type_Extension Equivalence Subset Conversion
P2 enum Classifier_Substitution_Rule: Classifier_Match Type_Extension Signature_Match
P4 enum Prototype_Substitution_Rule: Classifier_Match Type_Extension Signature_Match""",
    "Programming_Properties@2014": """
props Activate_Entrypoint Activate_Entrypoint_Call_Sequence Activate_Entrypoint_Source_Text
  Compute_Entrypoint Compute_Entrypoint_Call_Sequence Compute_Entrypoint_Source_Text
  Deactivate_Entrypoint Deactivate_Entrypoint_Call_Sequence Deactivate_Entrypoint_Source_Text
  Finalize_Entrypoint Finalize_Entrypoint_Call_Sequence Finalize_Entrypoint_Source_Text
  Initialize_Entrypoint Initialize_Entrypoint_Call_Sequence Initialize_Entrypoint_Source_Text
  Recover_Entrypoint Recover_Entrypoint_Call_Sequence Recover_Entrypoint_Source_Text Source_Language
  Source_Name Source_Text Supported_Source_Language Type_Source_Name Hardware_Description_Source_Text
  Hardware_Source_Language Device_Driver""",
    "Thread_Properties@2014": """
props Dispatch_Protocol Dispatch_Trigger Dispatch_Able POSIX_Scheduling_Policy Priority Criticality
  Time_Slot Concurrency_Control_Protocol Urgency Dequeue_Protocol Dequeued_Items
  Mode_Transition_Response Resumption_Policy Active_Thread_Handling_Protocol
  Active_Thread_Queue_Handling_Protocol Deactivation_Policy Runtime_Protection Subprogram_Call_Type
  Synchronized_Component
P3 enum POSIX_Scheduling_Policy: SCHED_FIFO SCHED_RR SCHED_OTHERS
P9 enum Dequeue_Protocol: OneItem MultipleItems AllItems
P11 enum Mode_Transition_Response: emergency planned
P12 enum Resumption_Policy: restart resume
P14 enum Active_Thread_Queue_Handling_Protocol: flush hold
P15 enum Deactivation_Policy: inactive unload
P17 enum Subprogram_Call_Type: Synchronous SemiSynchronous""",
    "Timing_Properties@2014": """
props Activate_Deadline:AADL_Project::Time_Units Activate_Execution_Time:AADL_Project::Time_Units
  Compute_Deadline:AADL_Project::Time_Units Compute_Execution_Time:AADL_Project::Time_Units
  Client_Subprogram_Execution_Time:AADL_Project::Time_Units
  Deactivate_Dealing:AADL_Project::Time_Units Deactivate_Execution_Time:AADL_Project::Time_Units
  Deadline:AADL_Project::Time_Units First_Dispatch_Time:AADL_Project::Time_Units
  Dispatch_Jitter:AADL_Project::Time_Units Dispatch_Offset:AADL_Project::Time_Units
  Execution_Time:AADL_Project::Time_Units Finalize_Deadline:AADL_Project::Time_Units
  Finalize_Execution_Time:AADL_Project::Time_Units Initialize_Deadline:AADL_Project::Time_Units
  Initialize_Execution_Time:AADL_Project::Time_Units Load_Deadline:AADL_Project::Time_Units
  Load_Time:AADL_Project::Time_Units Processor_Capacity:AADL_Project::Processor_Speed_Units
  Period:AADL_Project::Time_Units Recover_Deadline:AADL_Project::Time_Units
  Recover_Execution_Time:AADL_Project::Time_Units Startup_Deadline:AADL_Project::Time_Units
  Startup_Execution_Time:AADL_Project::Time_Units Clock_Jitter:AADL_Project::Time_Units
  Clock_Period:AADL_Project::Time_Units Clock_Period_Range:AADL_Project::Time_Units
  Process_Swap_Execution_Time:AADL_Project::Time_Units Reference_Processor
  Scheduler_Quantum:AADL_Project::Time_Units Thread_Swap_Execution_Time:AADL_Project::Time_Units
  Frame_Period:AADL_Project::Time_Units Slot_Time:AADL_Project::Time_Units""",
    "ARINC653@2017": """
props Module_Major_Frame:AADL_Project::Time_Units Sampling_Refresh_Period:AADL_Project::Time_Units
  Memory_Type Timeout:AADL_Project::Time_Units DAL Module_Version Module_Identifier
  Partition_Identifier Partition_Name System_Partition Error_Handling HM_Error_ID_Levels
  HM_Error_ID_Actions State_Information Queueing_Discipline Module_Schedule
  Time_Capacity:AADL_Project::Time_Units Deadline_Type
T0 enum Supported_Error_Code: Module_Config Module_Init Module_Scheduling Partition_Scheduling
  Partition_Config Partition_Handler Partition_Init Deadline_Miss Application_Error Numeric_Error
  Illegal_Request Stack_Overflow Memory_Violation Hardware_Fault Power_Fail
T1 enum Supported_Memory_Type: Data_Memory Code_Memory IO_Memory
T2 enum Supported_DAL_Type: LEVEL_A LEVEL_B LEVEL_C LEVEL_D LEVEL_E
T3 enum Error_Level_Type: Module_Level Partition_Level Process_Level
T4 record HM_Error_ID_Level_Type: ErrorIdentifier Description ErrorLevel ErrorCode
T5 record HM_Error_ID_Action_Type: ErrorIdentifier Description Action
T6 record State_Information_Type: Identifier Description
T7 enum Queueing_Discipline_Type: Fifo By_Priority
T8 record Schedule_Window: Partition Duration:AADL_Project::Time_Units Periodic_Processing_Start
P17 enum Deadline_Type: soft hard""",
    "SEI@2017": """
props SecurityLevel SafetyCriticality StreamMissRate NetWeight:SEI::WeightUnits
  GrossWeight:SEI::WeightUnits WeightLimit:SEI::WeightUnits StateRepresentation ProtocolQoS
  Partition_Latency:AADL_Project::Time_Units Is_Partition
  InstructionsPerDispatch:SEI::InstructionVolumeUnits MIPSCapacity:SEI::Processor_Speed_Units
  MIPSBudget:SEI::Processor_Speed_Units RAMCapacity:AADL_Project::Size_Units
  RAMBudget:AADL_Project::Size_Units ROMCapacity:AADL_Project::Size_Units
  ROMBudget:AADL_Project::Size_Units PowerCapacity:SEI::Power_Units PowerBudget:SEI::Power_Units
  PowerSupply:SEI::Power_Units BandWidthCapacity:AADL_Project::Data_Rate_Units
  BandWidthBudget:AADL_Project::Data_Rate_Units RAMActual:AADL_Project::Size_Units
  ROMActual:AADL_Project::Size_Units Data_Rate:SEI::Data_Rate Message_Rate:SEI::Message_Rate nsloc
  vdid_inspect Broadcast_Protocol Platform Price Model_References
T0 units WeightUnits: kg
T1 enum StateRepresentationType: State StateDelta
T2 enum ProtocolQoSType: GuaranteedDelivery SecureDelivery OrderedDelivery
T3 units InstructionVolumeUnits: IPD KIPD MIPD
T4 units Processor_Speed_Units: KIPS MIPS GIPS
T5 units Power_Units: mW W KW
T6 enum Reference_Kind_Type: any exist component connection behavior unknown
T7 enum Model_Source_Type: simulink scade geometry_stp sysml
T8 record Model_Reference: Model_Type Kind Filename Artifact
P24/U units Data_Rate: perSecond
P25/U units Message_Rate: perSecond""",
    "AADL_Project@2017": """
props
T0 enum Supported_Active_Thread_Handling_Protocols: abort
T1 enum Supported_Connection_Patterns: One_To_One All_To_All One_To_All All_To_One Next Previous
  Cyclic_Next Cyclic_Previous Odd_To_Odd Even_To_Even Next_Next Cyclic_Next_Next Previous_Previous
  Cyclic_Previous_Previous
T2 enum Supported_Concurrency_Control_Protocols: None_Specified Interrupt_Masking Maximum_Priority
  Priority_Inheritance Priority_Ceiling Spin_Lock Semaphore Protected_Access
T3 enum Supported_Dispatch_Protocols: Periodic Sporadic Aperiodic Timed Hybrid Background
T4 enum Supported_Queue_Processing_Protocols: Fifo
T5 enum Supported_Hardware_Source_Languages: VHDL
T6 enum Supported_Connection_QoS: GuaranteedDelivery OrderedDelivery SecureDelivery
T7 enum Supported_Scheduling_Protocols: Static Round_Robin_Protocol
  POSIX_1003_HIGHEST_PRIORITY_FIRST_PROTOCOL FixedTimeline Cooperative RMS DMS EDF SporadicServer
  SlackServer ARINC653
T8 enum Supported_Source_Languages: Ada95 Ada2005 C Java Simulink_6_5 SCADE
T9 enum Supported_Distributions: Fixed Poisson
T10 enum Supported_Classifier_Substitutions: Classifier_Match Type_Extension Signature_Match
T15 units Size_Units: bits Bytes KByte MByte GByte TByte
T16 units Time_Units: ps ns us ms sec min hr
T17 units Data_Rate_Units: bitsps Bytesps KBytesps MBytesps GBytesps
T18 units Data_Volume_Units: bitsps Bytesps KBytesps MBytesps GBytesps
T20 units Processor_Speed_Units: KIPS MIPS GIPS""",
    "Communication_Properties@2017": """
props Fan_Out_Policy Connection_Pattern Connection_Set Overflow_Handling_Protocol
  Queue_Processing_Protocol Queue_Size Required_Connection Timing Transmission_Type Input_Rate
  Input_Time Output_Rate Output_Time Subprogram_Call_Rate Transmission_Time
  Actual_Latency:AADL_Project::Time_Units Latency:AADL_Project::Time_Units
  Data_Rate:AADL_Project::Data_Rate_Units
T0 record Connection_Pair: src dst
T1 record IO_Time_Spec: Offset:AADL_Project::Time_Units Time
T2 enum IO_Reference_Time: Dispatch Start Completion Deadline NoIO Dynamic
T3 record Rate_Spec: Value_Range Rate_Unit Rate_Distribution
T3/F1 enum Rate_Spec.Rate_Unit: PerSecond PerDispatch
P0 enum Fan_Out_Policy: Broadcast RoundRobin Selective OnDemand
P3 enum Overflow_Handling_Protocol: DropOldest DropNewest Error
P7 enum Timing: sampled immediate delayed
P8 enum Transmission_Type: push pull
P14 record Transmission_Time: Fixed:AADL_Project::Time_Units PerByte:AADL_Project::Time_Units""",
    "Memory_Properties@2017": """
props Access_Right Access_Time Allowed_Message_Size:AADL_Project::Size_Units Assign_Time
  Base_Address Device_Register_Address Read_Time Code_Size:AADL_Project::Size_Units
  Data_Size:AADL_Project::Size_Units Heap_Size:AADL_Project::Size_Units
  Stack_Size:AADL_Project::Size_Units Source_Code_Size:AADL_Project::Size_Units
  Source_Data_Size:AADL_Project::Size_Units Source_Heap_Size:AADL_Project::Size_Units
  Source_Stack_Size:AADL_Project::Size_Units Byte_Count Memory_Size:AADL_Project::Size_Units
  Word_Size:AADL_Project::Size_Units Word_Space Write_Time
T0 enum Access_Rights: read_only write_only read_write by_method
P1 record Access_Time: First Last
P3 record Assign_Time: Fixed:AADL_Project::Time_Units PerByte:AADL_Project::Time_Units
P6 record Read_Time: Fixed:AADL_Project::Time_Units PerByte:AADL_Project::Time_Units
P19 record Write_Time: Fixed:AADL_Project::Time_Units PerByte:AADL_Project::Time_Units""",
    "Modeling_Properties@2017": """
props Acceptable_Array_Size Classifier_Matching_Rule Classifier_Substitution_Rule Implemented_As
  Prototype_Substitution_Rule
P1 enum Classifier_Matching_Rule: Classifier_Match Equivalence Subset Conversion
P2 enum Classifier_Substitution_Rule: Classifier_Match Type_Extension Signature_Match
P4 enum Prototype_Substitution_Rule: Classifier_Match Type_Extension Signature_Match""",
    "Timing_Properties@2017": """
props Activate_Deadline:AADL_Project::Time_Units Activate_Execution_Time:AADL_Project::Time_Units
  Compute_Deadline:AADL_Project::Time_Units Compute_Execution_Time:AADL_Project::Time_Units
  Client_Subprogram_Execution_Time:AADL_Project::Time_Units
  Deactivate_Deadline:AADL_Project::Time_Units Deactivate_Execution_Time:AADL_Project::Time_Units
  Deadline:AADL_Project::Time_Units First_Dispatch_Time:AADL_Project::Time_Units
  Dispatch_Jitter:AADL_Project::Time_Units Dispatch_Offset:AADL_Project::Time_Units
  Execution_Time:AADL_Project::Time_Units Finalize_Deadline:AADL_Project::Time_Units
  Finalize_Execution_Time:AADL_Project::Time_Units Initialize_Deadline:AADL_Project::Time_Units
  Initialize_Execution_Time:AADL_Project::Time_Units Load_Deadline:AADL_Project::Time_Units
  Load_Time:AADL_Project::Time_Units Processor_Capacity:AADL_Project::Processor_Speed_Units
  Period:AADL_Project::Time_Units Recover_Deadline:AADL_Project::Time_Units
  Recover_Execution_Time:AADL_Project::Time_Units Reference_Time
  Startup_Deadline:AADL_Project::Time_Units Startup_Execution_Time:AADL_Project::Time_Units
  Clock_Jitter:AADL_Project::Time_Units Clock_Period:AADL_Project::Time_Units
  Clock_Period_Range:AADL_Project::Time_Units Process_Swap_Execution_Time:AADL_Project::Time_Units
  Reference_Processor Scheduler_Quantum:AADL_Project::Time_Units
  Thread_Swap_Execution_Time:AADL_Project::Time_Units Frame_Period:AADL_Project::Time_Units
  Slot_Time:AADL_Project::Time_Units""",
    "AADL_Project@now": """
props
T0 enum Supported_Active_Thread_Handling_Protocols: abort
T1 enum Supported_Connection_Patterns: One_To_One All_To_All One_To_All All_To_One Next Previous
  Cyclic_Next Cyclic_Previous Odd_To_Odd Even_To_Even Next_Next Cyclic_Next_Next Previous_Previous
  Cyclic_Previous_Previous
T2 enum Supported_Concurrency_Control_Protocols: None_Specified Interrupt_Masking Maximum_Priority
  Priority_Inheritance Priority_Ceiling Spin_Lock Semaphore Protected_Access
T3 enum Supported_Dispatch_Protocols: Periodic Sporadic Aperiodic Timed Hybrid Background
T4 enum Supported_Queue_Processing_Protocols: Fifo
T5 enum Supported_Hardware_Source_Languages: VHDL
T6 enum Supported_Connection_QoS: GuaranteedDelivery OrderedDelivery SecureDelivery
T7 enum Supported_Scheduling_Protocols: Static Round_Robin_Protocol
  POSIX_1003_HIGHEST_PRIORITY_FIRST_PROTOCOL FixedTimeline Cooperative RMS DMS EDF SporadicServer
  SlackServer ARINC653
T8 enum Supported_Source_Languages: Ada95 Ada2005 C Java Simulink_6_5 SCADE
T9 enum Supported_Distributions: Fixed Poisson
T10 enum Supported_Classifier_Substitutions: Classifier_Match Type_Extension Signature_Match
T15 units Size_Units: bits Bytes KByte MByte GByte TByte KiByte MiByte GiByte TiByte
T16 units Time_Units: ps ns us ms sec min hr
T17 units Data_Rate_Units: bitsps kbps Mbps Gbps Bytesps KBytesps MBytesps GBytesps
T18 units Processor_Speed_Units: KIPS MIPS GIPS
T19 units Data_Volume_Units: bitsps Bytesps KBytesps MBytesps GBytesps""",
    "Memory_Properties@now": """
props Access_Right Access_Time Allowed_Message_Size:AADL_Project::Size_Units Assign_Time
  Base_Address Device_Register_Address Read_Time Code_Size:AADL_Project::Size_Units
  Data_Size:AADL_Project::Size_Units Heap_Size:AADL_Project::Size_Units
  Stack_Size:AADL_Project::Size_Units Memory_Size:AADL_Project::Size_Units
  Word_Size:AADL_Project::Size_Units Word_Space Write_Time Source_Code_Size:AADL_Project::Size_Units
  Source_Data_Size:AADL_Project::Size_Units Source_Heap_Size:AADL_Project::Size_Units
  Source_Stack_Size:AADL_Project::Size_Units Byte_Count
T0 enum Access_Rights: read_only write_only read_write by_method
P1 record Access_Time: First Last
P3 record Assign_Time: Fixed:AADL_Project::Time_Units PerByte:AADL_Project::Time_Units
P6 record Read_Time: Fixed:AADL_Project::Time_Units PerByte:AADL_Project::Time_Units
P14 record Write_Time: Fixed:AADL_Project::Time_Units PerByte:AADL_Project::Time_Units""",
    "ARINC653@now": """
props Module_Major_Frame:AADL_Project::Time_Units Sampling_Refresh_Period:AADL_Project::Time_Units
  Memory_Kind Timeout:AADL_Project::Time_Units DAL Module_Version Module_Identifier
  Partition_Identifier Partition_Name System_Partition Error_Handling HM_Error_ID_Levels
  HM_Error_ID_Actions State_Information Queueing_Discipline Module_Schedule
  Time_Capacity:AADL_Project::Time_Units Deadline_Type
T0 enum Supported_Error_Code: Module_Config Module_Init Module_Scheduling Partition_Scheduling
  Partition_Config Partition_Handler Partition_Init Deadline_Miss Application_Error Numeric_Error
  Illegal_Request Stack_Overflow Memory_Violation Hardware_Fault Power_Fail
T1 enum Supported_Memory_Kind: Memory_Data Memory_Code
T2 enum Supported_DAL_Type: LEVEL_A LEVEL_B LEVEL_C LEVEL_D LEVEL_E
T3 enum Error_Level_Type: Module_Level Partition_Level Process_Level
T4 record HM_Error_ID_Level_Type: ErrorIdentifier Description ErrorLevel ErrorCode
T5 record HM_Error_ID_Action_Type: ErrorIdentifier Description Action
T6 record State_Information_Type: Identifier Description
T7 enum Queueing_Discipline_Type: Fifo By_Priority
T8 record Schedule_Window: Partition Duration:AADL_Project::Time_Units Periodic_Processing_Start
P17 enum Deadline_Type: soft hard""",
    "Code_Generation_Properties@now": """
props Convention Parameter_Usage Return_Parameter
P0 enum Convention: AADL Legacy
P1 enum Parameter_Usage: By_Value By_Reference""",
    "Physical@now": """
props Voltage:Physical::Voltage_Units
T1 units Voltage_Units: mV V KV""",
    "SEI@now": """
props SecurityLevel SafetyCriticality StreamMissRate NetWeight:SEI::WeightUnits
  GrossWeight:SEI::WeightUnits WeightLimit:SEI::WeightUnits StateRepresentation ProtocolQoS
  Partition_Latency:AADL_Project::Time_Units Is_Partition
  InstructionsPerDispatch:SEI::InstructionVolumeUnits MIPSCapacity:SEI::Processor_Speed_Units
  MIPSBudget:SEI::Processor_Speed_Units RAMCapacity:AADL_Project::Size_Units
  RAMBudget:AADL_Project::Size_Units ROMCapacity:AADL_Project::Size_Units
  ROMBudget:AADL_Project::Size_Units PowerCapacity:SEI::Power_Units PowerBudget:SEI::Power_Units
  PowerSupply:SEI::Power_Units BandWidthCapacity:AADL_Project::Data_Rate_Units
  BandWidthBudget:AADL_Project::Data_Rate_Units RAMActual:AADL_Project::Size_Units
  ROMActual:AADL_Project::Size_Units Data_Rate:SEI::Data_Rate Message_Rate:SEI::Message_Rate nsloc
  vdid_inspect Broadcast_Protocol Platform Price Model_References
  Response_Time:AADL_Project::Time_Units Mode_Domain
T0 units WeightUnits: kg
T1 enum StateRepresentationType: State StateDelta
T2 enum ProtocolQoSType: GuaranteedDelivery SecureDelivery OrderedDelivery
T3 units InstructionVolumeUnits: IPD KIPD MIPD
T4 units Processor_Speed_Units: KIPS MIPS GIPS
T5 units Power_Units: mW W KW
T6 enum Reference_Kind_Type: any exist component connection behavior unknown
T7 enum Model_Source_Type: simulink scade geometry_stp sysml
T8 record Model_Reference: Model_Type Kind Filename Artifact
P24/U units Data_Rate: perSecond
P25/U units Message_Rate: perSecond""",
    "ARP4761@now": """
props Hazards
T0 enum SeverityClassification: Catastrophic Hazardous SevereMajor Major Minor NoEffect
T1 enum ProbabilityLabels: Frequent Probable Remote ExtremelyRemote ExtremelyImprobable
P0/E record Hazards: CrossReference HazardTitle Description Failure FailureEffect Phases Environment
  Mishap Risk FailureCondition FailureConditionClassification QualitativeProbability
  QuantitativeProbability QualitativeProbabilityObjective QuantitativeProbabilityObjective
  DevelopmentAssuranceLevel VerificationMethod SafetyReport Comment""",
    "EMV2@now": """
props OccurrenceDistribution ExposurePeriod DurationDistribution PropagationTimeDelay
  TransientFailureRatio RecoveryFailureRatio StateKind DetectionMechanism FaultKind Persistence
  Severity Likelihood Hazards Description HazardAllocation
T0 record DistributionSpecification: ProbabilityValue OccurrenceRate MeanValue StandardDeviation
  ShapeParameter ScaleParameter SuccessCount SampleCount Probability Distribution
T1 enum DistributionFunction: Fixed Poisson Exponential Normal Gauss Weibull Binominal
T2 record DurationDistributionSpecification: Duration:AADL_Project::Time_Units Distribution
T3 enum StateKindEnum: Working NonWorking
T4 enum FaultKindEnum: Design Operational
T5 enum PersistenceEnum: Permanent Transient Singleton
T8 enum LikelihoodLabels: A B C D E F
T9 enum DALLabels: A B C D E
P12/E record Hazards: CrossReference HazardTitle Description Failure FailureEffect Phases
  Environment Mishap FailureCondition Risk Severity Likelihood Probability TargetSeverity
  TargetLikelihood DevelopmentAssuranceLevel VerificationMethod SafetyReport Comment
P14 record HazardAllocation: AssumedProbability ExposureTime:AADL_Project::Time_Units Notes""",
    "MILSTD882@now": """
props Hazards
T0 enum SeverityLabels: Catastrophic Critical Marginal Negligible
T2 enum ProbabilityLabels: Frequent Probable Occasional Remote Improbable Eliminated
T3 enum ProbabilityLevelLabels: A B C D E F
P0/E record Hazards: CrossReference HazardTitle Description Failure FailureEffect Phases Environment
  Mishap Risk SeverityLevel SeverityCategory QualitativeProbability ProbabilityLevel
  QuantitativeProbability TargetSeverityLevel TargetProbabilityLevel VerificationMethod SafetyReport
  Comment""",
}

_ERA_SETS: dict[str, dict[str, tuple[str, str]]] = {
    "2014": {
        "ARINC429": ("org.osate.contribution.sei", "ARINC429@2014"),
        "ARINC653": ("org.osate.contribution.sei", "ARINC653@2014"),
        "Data_Model": ("org.osate.contribution.sei", "Data_Model@2014"),
        "SEI": ("org.osate.contribution.sei", "SEI@2014"),
        "AADL_Project": ("org.osate.workspace", "AADL_Project@2014"),
        "Communication_Properties": ("org.osate.workspace", "Communication_Properties@2014"),
        "Deployment_Properties": ("org.osate.workspace", "Deployment_Properties@2014"),
        "Memory_Properties": ("org.osate.workspace", "Memory_Properties@2014"),
        "Modeling_Properties": ("org.osate.workspace", "Modeling_Properties@2014"),
        "Programming_Properties": ("org.osate.workspace", "Programming_Properties@2014"),
        "Thread_Properties": ("org.osate.workspace", "Thread_Properties@2014"),
        "Timing_Properties": ("org.osate.workspace", "Timing_Properties@2014"),
    },
    "2017-2020": {
        "ARINC429": ("org.osate.contribution.sei", "ARINC429@2014"),
        "ARINC653": ("org.osate.contribution.sei", "ARINC653@2017"),
        "Data_Model": ("org.osate.contribution.sei", "Data_Model@2014"),
        "SEI": ("org.osate.contribution.sei", "SEI@2017"),
        "AADL_Project": ("org.osate.workspace", "AADL_Project@2017"),
        "Communication_Properties": ("org.osate.workspace", "Communication_Properties@2017"),
        "Deployment_Properties": ("org.osate.workspace", "Deployment_Properties@2014"),
        "Memory_Properties": ("org.osate.workspace", "Memory_Properties@2017"),
        "Modeling_Properties": ("org.osate.workspace", "Modeling_Properties@2017"),
        "Programming_Properties": ("org.osate.workspace", "Programming_Properties@2014"),
        "Thread_Properties": ("org.osate.workspace", "Thread_Properties@2014"),
        "Timing_Properties": ("org.osate.workspace", "Timing_Properties@2017"),
    },
    "current": {
        "AADL_Project": ("org.osate.aadl2.contrib", "AADL_Project@now"),
        "Communication_Properties": ("org.osate.aadl2.contrib", "Communication_Properties@2017"),
        "Deployment_Properties": ("org.osate.aadl2.contrib", "Deployment_Properties@2014"),
        "Memory_Properties": ("org.osate.aadl2.contrib", "Memory_Properties@now"),
        "Modeling_Properties": ("org.osate.aadl2.contrib", "Modeling_Properties@2017"),
        "Programming_Properties": ("org.osate.aadl2.contrib", "Programming_Properties@2014"),
        "Thread_Properties": ("org.osate.aadl2.contrib", "Thread_Properties@2014"),
        "Timing_Properties": ("org.osate.aadl2.contrib", "Timing_Properties@2017"),
        "ARINC429": ("org.osate.contribution.sei", "ARINC429@2014"),
        "ARINC653": ("org.osate.contribution.sei", "ARINC653@now"),
        "Code_Generation_Properties": ("org.osate.contribution.sei", "Code_Generation_Properties@now"),
        "Data_Model": ("org.osate.contribution.sei", "Data_Model@2014"),
        "Physical": ("org.osate.contribution.sei", "Physical@now"),
        "SEI": ("org.osate.contribution.sei", "SEI@now"),
        "ARP4761": ("org.osate.aadl2.errormodel.contrib", "ARP4761@now"),
        "EMV2": ("org.osate.aadl2.errormodel.contrib", "EMV2@now"),
        "MILSTD882": ("org.osate.aadl2.errormodel.contrib", "MILSTD882@now"),
    },
}

# --------------------------------------------------------------------------- URI forms

#: Plugin folder (the path segment before ``resources/…``) → the eras whose predeclared sets live there.
_PLUGIN_ERAS: dict[str, tuple[str, ...]] = {
    "Plugin_Resources": ("2014",),
    "org.osate.workspace": ("2017-2020",),
    "org.osate.aadl2.contrib": ("current",),
    "org.osate.contribution.sei": ("2017-2020", "current"),
    "org.osate.aadl2.errormodel.contrib": ("current",),
}

_URI_RE = re.compile(
    r"(?:^|/)(?:(Plugin_Resources)/|"
    r"(org\.osate\.workspace|org\.osate\.aadl2\.contrib|org\.osate\.contribution\.sei"
    r"|org\.osate\.aadl2\.errormodel\.contrib)/resources/(?:[A-Za-z_]+/)+)"
    r"([A-Za-z][A-Za-z0-9_]*)\.aadl$"
)

_PLUGIN_PREFIX = {
    "org.osate.workspace": (
        "platform:/plugin/org.osate.workspace/resources/properties/Predeclared_Property_Sets/"
    ),
    "org.osate.aadl2.contrib": (
        "platform:/plugin/org.osate.aadl2.contrib/resources/properties/Predeclared_Property_Sets/"
    ),
    "org.osate.contribution.sei": "platform:/plugin/org.osate.contribution.sei/resources/properties/",
    "org.osate.aadl2.errormodel.contrib": (
        "platform:/plugin/org.osate.aadl2.errormodel.contrib/resources/properties/"
    ),
}


@dataclass(frozen=True)
class PredeclaredUri:
    """A URI that names one of OSATE's predeclared (or SEI/EMV2-contributed) property sets."""

    property_set: str
    plugin: str
    eras: tuple[str, ...]


@lru_cache(maxsize=4096)
def classify_uri(uri: str) -> PredeclaredUri | None:
    """The predeclared set a URI names, with the eras that wrote that URI form; None otherwise.

    Any prefix is accepted (``platform:/plugin/``, ``../../``, a resolved workspace path), as
    EMF makes plugin URIs relative when the workspace holds a copy of the plugin.
    """
    match = _URI_RE.search(uri)
    if match is None:
        return None
    plugin = match.group(1) or match.group(2)
    return PredeclaredUri(match.group(3), plugin, _PLUGIN_ERAS[plugin])


def normalize_fragment(fragment: str) -> str:
    """``//@a.1/@b`` and ``/0/@a.1/@b`` → ``@a.1/@b`` (the root object's path, era-neutral)."""
    if fragment.startswith("//"):
        return fragment[2:]
    if fragment.startswith("/0/"):
        return fragment[3:]
    if fragment in ("/", "/0"):
        return ""
    return fragment


# --------------------------------------------------------------------------- tables


@dataclass(frozen=True)
class Literal:
    """A decoded positional reference: an enumeration literal, a unit literal or a record field."""

    era: str
    property_set: str
    path: str  # era-neutral fragment, e.g. @ownedPropertyType.16/@ownedLiteral.3
    kind: str  # "enum" | "units" | "field"
    type_name: str  # qualified: AADL_Project::Time_Units, Data_Model::Data_Representation
    name: str  # the literal (ms, Periodic) or field name (Fixed)
    index: int
    units: str | None = None  # for a field: the units type of its values, when they carry units


@dataclass
class _Container:
    path: str
    kind: str  # enum | units | record
    type_name: str  # qualified
    entries: list[tuple[str, str | None]]


@dataclass
class _SetFacts:
    name: str
    plugin: str
    properties: list[tuple[str, str | None]]
    containers: dict[str, _Container] = field(default_factory=dict)
    by_type: dict[str, _Container] = field(default_factory=dict)
    property_units: dict[str, str | None] = field(default_factory=dict)


def _expand(abbrev: str) -> str:
    parts = abbrev.split("/")
    head = parts[0]
    number = head[1:]
    out = {
        "T": f"@ownedPropertyType.{number}",
        "P": f"@ownedProperty.{number}/@ownedPropertyType",
        "C": f"@ownedPropertyConstant.{number}/@ownedPropertyType",
    }[head[0]]
    for part in parts[1:]:
        if part.startswith("F"):
            out += f"/@ownedField.{part[1:]}/@ownedPropertyType"
        else:
            out += {"E": "/@ownedElementType", "U": "/@ownedUnitsType", "N": "/@ownedNumberType"}[part]
    return out


def _entry(token: str) -> tuple[str, str | None]:
    name, _, units = token.partition(":")
    return name, units or None


def _parse_block(set_name: str, plugin: str, text: str) -> _SetFacts:
    lines: list[str] = []
    for raw in text.strip().splitlines():
        if raw.startswith("  ") and lines:
            lines[-1] += " " + raw.strip()
        else:
            lines.append(raw.strip())
    facts = _SetFacts(set_name, plugin, [])
    for line in lines:
        if line.startswith("props"):
            facts.properties = [_entry(t) for t in line.split()[1:]]
            continue
        head, _, rest = line.partition(":")
        abbrev, kind, local = head.split()
        container = _Container(
            _expand(abbrev), kind, f"{set_name}::{local}", [_entry(t) for t in rest.split()]
        )
        facts.containers[container.path] = container
        facts.by_type.setdefault(local.lower(), container)
    facts.property_units = {name.lower(): units for name, units in facts.properties}
    return facts


class EraTable:
    """The decoding facts of one era: positional path ↔ literal, property order, units types."""

    def __init__(self, era: str) -> None:
        if era not in _ERA_SETS:
            raise UsageError(f"unknown OSATE era {era!r} (known: {', '.join(ERAS)})")
        self.era = era
        self._sets: dict[str, _SetFacts] = {}
        for set_name, (plugin, key) in _ERA_SETS[era].items():
            self._sets[set_name.lower()] = _parse_block(set_name, plugin, _BLOCKS[key])

    def property_sets(self) -> list[str]:
        return sorted(facts.name for facts in self._sets.values())

    def has_set(self, property_set: str) -> bool:
        return property_set.lower() in self._sets

    def plugin_of(self, property_set: str) -> str | None:
        facts = self._sets.get(property_set.lower())
        return facts.plugin if facts else None

    def literal(self, property_set: str, path: str) -> Literal | None:
        """Decode ``@…/@ownedLiteral.k`` or ``@…/@ownedField.k`` (era-neutral path); None if absent."""
        return _decoded_literal(self.era, property_set, path)

    def _decode_literal(self, property_set: str, path: str) -> Literal | None:
        facts = self._sets.get(property_set.lower())
        if facts is None:
            return None
        container_path, _, last = path.rpartition("/")
        feature, _, number = last.partition(".")
        container = facts.containers.get(container_path)
        if container is None or not number.isdigit():
            return None
        index = int(number)
        if feature == "@ownedLiteral" and container.kind in ("enum", "units"):
            kind = container.kind
        elif feature == "@ownedField" and container.kind == "record":
            kind = "field"
        else:
            return None
        if index >= len(container.entries):
            return None
        name, units = container.entries[index]
        return Literal(self.era, facts.name, path, kind, container.type_name, name, index, units)

    def literal_path(self, property_set: str, type_name: str, name: str) -> str | None:
        """The era-neutral path of literal/field ``name`` of ``type_name`` (the reverse of :meth:`literal`).

        ``type_name`` may be qualified (``AADL_Project::Time_Units``) or local; literal names
        match case-insensitively, as in AADL.
        """
        facts = self._sets.get(property_set.lower())
        if facts is None:
            return None
        container = facts.by_type.get(type_name.rpartition("::")[2].lower())
        if container is None:
            return None
        wanted = name.lower()
        for index, (entry, _units) in enumerate(container.entries):
            if entry.lower() == wanted:
                step = "@ownedField" if container.kind == "record" else "@ownedLiteral"
                return f"{container.path}/{step}.{index}"
        return None

    def property_name(self, property_set: str, index: int) -> str | None:
        """The property declared at ``@ownedProperty.<index>`` of a set, qualified; None if absent."""
        facts = self._sets.get(property_set.lower())
        if facts is None or not 0 <= index < len(facts.properties):
            return None
        return f"{facts.name}::{facts.properties[index][0]}"

    def property_index(self, qualified_property: str) -> int | None:
        set_name, _, local = qualified_property.rpartition("::")
        facts = self._sets.get(set_name.lower())
        if facts is None:
            return None
        for index, (name, _units) in enumerate(facts.properties):
            if name.lower() == local.lower():
                return index
        return None

    def property_units(self, qualified_property: str) -> str | None:
        """The units type (``AADL_Project::Time_Units``) a predeclared property's numbers carry."""
        set_name, _, local = qualified_property.rpartition("::")
        facts = self._sets.get(set_name.lower())
        if facts is None:
            return None
        return facts.property_units.get(local.lower())


@lru_cache(maxsize=4096)
def _decoded_literal(era: str, property_set: str, path: str) -> Literal | None:
    """:meth:`EraTable.literal`, decoded once per (era, set, path): the tables are immutable."""
    return table(era)._decode_literal(property_set, path)


@cache
def table(era: str) -> EraTable:
    """The (immutable, cached) decoding table of an era."""
    return EraTable(era)


def predeclared_uri(era: str, property_set: str) -> str:
    """The URI an OSATE of ``era`` writes for a predeclared set (2014: workspace-relative)."""
    plugin = table(era).plugin_of(property_set)
    if plugin is None:
        raise UsageError(f"{property_set} is not a predeclared property set of the {era} era")
    name = table(era)._sets[property_set.lower()].name
    if era == "2014":
        return f"Plugin_Resources/{name}.aadl"
    return _PLUGIN_PREFIX[plugin] + f"{name}.aadl"


def fragment(era: str, path: str) -> str:
    """The fragment an OSATE of ``era`` writes for an era-neutral path (``//…`` in 2014, ``/0/…`` since)."""
    return ("//" if era == "2014" else "/0/") + path


# --------------------------------------------------------------------------- choosing the era


@dataclass(frozen=True)
class HrefUse:
    """One positional reference into a property set, with what it is used for.

    ``role``: ``unit`` (a number's unit), ``enum`` (a named value), ``field`` (a record field's
    property) or ``property`` (a property association's property). ``property`` is the
    qualified property whose value holds the reference, ``field_href`` the (uri, fragment) of
    the record field whose value holds it, when that is where it sits.
    """

    uri: str
    fragment: str
    role: str
    property: str | None = None
    field_href: tuple[str, str] | None = None


@dataclass(frozen=True)
class EraChoice:
    """The era chosen for a file and what did not decode.

    ``era`` is the file's era; ``set_eras`` names, for property sets whose references only
    decode with another era's table (OSATE shipped some contributed sets ahead of the
    predeclared ones), the era used for that set. ``uri_eras`` are the eras the URI forms
    allow, ``consistent_eras`` those whose tables decode every reference, ``problems`` the
    references that do not decode (with the reason) in the era finally used for their set.
    """

    era: str | None
    uri_eras: tuple[str, ...]
    problems: tuple[tuple[HrefUse, str], ...] = ()
    consistent_eras: tuple[str, ...] = ()
    set_eras: dict[str, str] = field(default_factory=dict)

    def era_of(self, property_set: str) -> str | None:
        return self.set_eras.get(property_set, self.era)


_KIND_OF_ROLE = {"unit": "units", "enum": "enum", "field": "field"}


def _context_property(era: str, prop: str | None) -> str | None:
    """The qualified property of a use's context; a positional ``uri#fragment`` is decoded in ``era``."""
    if prop is None or "#" not in prop:
        return prop
    uri, _, frag = prop.partition("#")
    pre = classify_uri(uri)
    match = re.fullmatch(r"@ownedProperty\.(\d+)", normalize_fragment(frag))
    if pre is None or match is None:
        return None
    return table(era).property_name(pre.property_set, int(match.group(1)))


def _property_matches(literal: Literal, prop: str | None) -> bool:
    """An anonymous property type (``@ownedProperty.N/…``) must belong to the property in use."""
    if prop is None or not literal.path.startswith("@ownedProperty."):
        return True
    owner = literal.type_name.rpartition("::")[2].partition(".")[0]
    set_name, _, local = prop.rpartition("::")
    return owner.lower() == local.lower() and set_name.lower() == literal.property_set.lower()


@lru_cache(maxsize=8192)
def check_use(era: str, use: HrefUse) -> str | None:
    """Why ``use`` does not decode consistently in ``era`` (None when it does)."""
    pre = classify_uri(use.uri)
    if pre is None:
        return "not a predeclared property set"
    tab = table(era)
    if not tab.has_set(pre.property_set):
        return f"{pre.property_set} is not predeclared in the {era} era"
    path = normalize_fragment(use.fragment)
    if use.role == "property":
        match = re.fullmatch(r"@ownedProperty\.(\d+)", path)
        if match is None or tab.property_name(pre.property_set, int(match.group(1))) is None:
            return f"no property at {path} in {pre.property_set}"
        return None
    literal = tab.literal(pre.property_set, path)
    if literal is None:
        return f"no literal at {path} in {pre.property_set}"
    prop = _context_property(era, use.property)
    if (
        prop is not None
        and prop.rpartition("::")[0].lower() == pre.property_set.lower()
        and tab.property_index(prop) is None
    ):
        # a literal of the set that declares the property, which this era's copy of the set does
        # not declare (ARINC653::Memory_Type is Memory_Kind today): the positions are another era's
        return f"{prop} is not declared in the {era} {prop.rpartition('::')[0]}"
    if literal.kind != _KIND_OF_ROLE.get(use.role):
        return f"{path} in {pre.property_set} is a {literal.kind} of {literal.type_name}, not a {use.role}"
    if use.role in ("enum", "field") and not _property_matches(literal, prop):
        return f"{literal.type_name} does not belong to property {prop}"
    if use.role == "unit":
        expected = None
        if use.field_href is not None:
            field_pre = classify_uri(use.field_href[0])
            if field_pre is not None:
                owner = tab.literal(field_pre.property_set, normalize_fragment(use.field_href[1]))
                expected = owner.units if owner is not None else None
        elif prop is not None:
            expected = tab.property_units(prop)
        if expected is not None and expected.lower() != literal.type_name.lower():
            return f"unit {literal.name} of {literal.type_name}, but {prop} takes {expected}"
    return None


def choose_era(uses: Iterable[HrefUse], uris: Iterable[str] = ()) -> EraChoice:
    """Pick the era whose tables decode every positional reference into a predeclared set.

    The URI forms of ``uses`` and of the further ``uris`` the file refers to (properties by
    name, classifiers) narrow the candidates: ``Plugin_Resources`` → 2014,
    ``org.osate.workspace`` → 2017-2020, ``org.osate.aadl2.contrib`` → current. A candidate's
    table must decode every reference to the right kind of element (a unit to a units type,
    a named value to an enumeration, a field to a record, an anonymous type to the property
    in use), and a unit must belong to the units type of the property it qualifies. The file's
    era is the one the URI forms name, or else the candidate with the fewest problems
    (URI-implied eras first, newest first). Then, per property set whose references do not all
    decode in that era, the nearest other era that decodes all of them is used for that set;
    what still does not decode is reported.
    """
    uses = list(uses)
    predeclared = [u for u in uses if classify_uri(u.uri) is not None]
    implied: set[str] | None = None
    for uri in [u.uri for u in predeclared] + list(uris):
        pre = classify_uri(uri)
        if pre is not None:
            implied = set(pre.eras) if implied is None else implied & set(pre.eras)
    uri_eras = tuple(e for e in reversed(ERAS) if implied and e in implied)
    if not predeclared:
        return EraChoice(uri_eras[0] if len(uri_eras) == 1 else None, uri_eras)
    order = list(uri_eras) + [e for e in reversed(ERAS) if e not in uri_eras]
    problems_of: dict[str, list[tuple[HrefUse, str]]] = {}

    def problems(era: str) -> list[tuple[HrefUse, str]]:
        if era not in problems_of:
            problems_of[era] = [(use, why) for use in predeclared if (why := check_use(era, use))]
        return problems_of[era]

    # The URI form decides when it names one era; otherwise the first candidate that decodes
    # everything (URI-implied eras first, newest first), or else the one with the fewest problems.
    if len(uri_eras) == 1:
        era = uri_eras[0]
    else:
        era = next((e for e in order if not problems(e)), None) or min(order, key=lambda e: len(problems(e)))
    problems(era)
    consistent = tuple(e for e in order if e in problems_of and not problems_of[e])
    nearest = sorted(
        (e for e in ERAS if e != era), key=lambda e: (abs(ERAS.index(e) - ERAS.index(era)), -ERAS.index(e))
    )
    set_eras: dict[str, str] = {}
    # A set whose URIs name one era other than the file's is decoded in that era when it can be:
    # OSATE renamed some literals in place (ARINC653's Data_Memory is Memory_Data today), so a
    # file that keeps an old literal writes that set in the old layout, under the old URI form.
    uri_eras_of: dict[str, set[str]] = {}
    for use in predeclared:
        pre = classify_uri(use.uri)
        eras_here = set(pre.eras)  # type: ignore[union-attr]
        known = uri_eras_of.get(pre.property_set)  # type: ignore[union-attr]
        uri_eras_of[pre.property_set] = eras_here if known is None else known & eras_here  # type: ignore[union-attr]
    for set_name, named in sorted(uri_eras_of.items()):
        if len(named) == 1 and era not in named:
            (only,) = named
            set_uses = [u for u in predeclared if classify_uri(u.uri).property_set == set_name]  # type: ignore[union-attr]
            if all(check_use(only, u) is None for u in set_uses):
                set_eras[set_name] = only
    remaining: list[tuple[HrefUse, str]] = []
    by_set: dict[str, list[tuple[HrefUse, str]]] = {}
    for use, why in problems(era):
        set_name = classify_uri(use.uri).property_set  # type: ignore[union-attr]
        if set_name in set_eras:
            continue
        by_set.setdefault(set_name, []).append((use, why))
    for set_name, failing in by_set.items():
        set_uses = [u for u in predeclared if classify_uri(u.uri).property_set == set_name]  # type: ignore[union-attr]
        other = next((e for e in nearest if all(check_use(e, u) is None for u in set_uses)), None)
        if other is not None:
            set_eras[set_name] = other
        else:
            remaining.extend(failing)
    return EraChoice(era, uri_eras, tuple(remaining), consistent, set_eras)
