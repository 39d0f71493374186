# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""Simulation.get_state() / set_state(): a state taken at t, flown on, restored and flown again
gives the same bits, in the same object or a new one, driven or not; a state of another
configuration and a stage that cannot be saved are refused by name."""

import numpy as np
import pytest

import mjformation
from conftest import short


def flown(sim, steps):
    sim.step(steps)
    return sim.states.copy(), sim.setpoints.copy(), sim.controls.copy()


def same(a, b):
    return all(np.array_equal(x, y, equal_nan=True) for x, y in zip(a, b))


@pytest.mark.parametrize("extra", [{}, {"vehicles.rotor_model": "wrench"},
                                   {"sensors.preset": "typical", "wind.turbulence": "moderate"},
                                   {"execution.mode": "per_agent", "network.rate": 100.0,
                                    "network.latency": 0.02, "network.loss": 0.1}])
def test_a_restored_state_flies_the_same_bits(source, extra):
    # Given Exp 2 with a seeded random leader, its state taken at t = 0.7 s
    experiment = source / "experiments/leaders/exp2_random_accel.toml"
    overrides = {**short(2.0), **extra}
    sim = mjformation.Simulation(experiment, set=overrides)
    sim.step(700)
    state = sim.get_state()
    # When it flies on, is restored and flies again, and a new Simulation does the same
    first = flown(sim, 900)
    again = flown(sim.set_state(state), 900)
    other = flown(mjformation.Simulation(experiment, set=overrides).set_state(state), 900)
    uninterrupted = flown(mjformation.Simulation(experiment, set=overrides), 1600)
    # Then every flight is the same, bit for bit
    assert sim.time == pytest.approx(1.6)
    assert same(first, again) and same(first, other) and same(first, uninterrupted)


def test_a_driven_state_restores_the_flight_and_its_events(exp2):
    # Given a driven Exp 2, its state after ten commanded samples
    sim = mjformation.Simulation(exp2, set=short(1.5), driven=True)
    for _ in range(10):
        sim.step(sim.law_actions * 1.2)
    state = sim.get_state()

    def fly():
        for _ in range(10):
            sim.step(sim.law_actions * 0.8)
        return sim.states.copy(), sim.setpoints.copy(), [e["text"] for e in sim.events]

    # When it flies on twice from that state
    first = fly()
    sim.set_state(state)
    second = fly()
    # Then the flights and the safety events seen are the same
    assert same(first[:2], second[:2])
    assert first[2] == second[2]

def test_another_configuration_and_unsaved_stages_are_refused(exp2):
    state = mjformation.Simulation(exp2, set=short(1.0)).get_state()
    other = mjformation.Simulation(exp2, set={**short(1.0), "run.seed": 5})
    with pytest.raises(ValueError, match="another configuration .*sha256 [0-9a-f]{64}"):
        other.set_state(state)
    driven = mjformation.Simulation(exp2, set=short(1.0), driven=True)
    with pytest.raises(ValueError, match="'no safety' was expected|'safety' was expected"):
        driven.set_state(state)
