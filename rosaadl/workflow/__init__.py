"""The workflow layer: what reads inputs, runs the transformations and analyses, and writes outputs.

Below it, importers read files into models, transformations go from model to model without
touching files, analyses compute from an instance, and exporters write models out. The modules
here join them for the command line and for users of the Python API (converting a ROSMOD project
folder, binding deployments to the library's robots, listing the library and adding profiles).
"""
