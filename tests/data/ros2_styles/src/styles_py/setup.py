from setuptools import setup

setup(name="styles_py", packages=["styles_py"])
