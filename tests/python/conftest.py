"""Shared by the Python tests (run.sh runs them on NP ranks, every rank the same tests)."""
import os
import pathlib

import pytest
from mpi4py import MPI


@pytest.fixture
def comm():
    return MPI.COMM_WORLD


@pytest.fixture
def work():
    """The run's scratch folder (run.sh made the references there)."""
    return pathlib.Path(os.environ["SORTLAST_TEST_WORK"])


@pytest.fixture
def rank():
    return MPI.COMM_WORLD.Get_rank()
