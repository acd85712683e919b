use super::*;

const PERIOD: f64 = 0.001;

fn shaper(kind: ShaperType, frequency: f64, damping: f64) -> Shaper {
    match Shaper::new(kind, frequency, damping, PERIOD, 0.0) {
        Ok(s) => s,
        Err(e) => panic!("shaper refused: {e}"),
    }
}

/// A unit step at tick 10: the output is the sum of the impulses whose delay has passed.
#[test]
fn shaped_step_is_the_sum_of_delayed_steps() {
    // ζ = 0 and 5 Hz: half a period is 100 ticks exactly.
    for kind in [ShaperType::Zv, ShaperType::Zvd, ShaperType::Ei] {
        let mut s = shaper(kind, 5.0, 0.0);
        let impulses: Vec<(f64, f64)> = s.impulses().collect();
        for tick in 0..400u32 {
            let input = if tick >= 10 { 1.0 } else { 0.0 };
            let out = s.next(input);
            let t = f64::from(tick) * PERIOD;
            let expected: f64 = impulses
                .iter()
                .filter(|(_, delay)| t + 1e-12 >= 0.010 + delay)
                .map(|(a, _)| a)
                .sum();
            assert!(
                (out - expected).abs() < 1e-12,
                "{kind:?} tick {tick}: {out} vs {expected}"
            );
        }
        assert!(s.is_settled());
    }
}

#[test]
fn zv_amplitudes_follow_the_damping() {
    let s = shaper(ShaperType::Zv, 10.0, 0.1);
    let v: Vec<(f64, f64)> = s.impulses().collect();
    let root = (1.0f64 - 0.01).sqrt();
    let k = (-0.1 * std::f64::consts::PI / root).exp();
    assert!((v[0].0 - 1.0 / (1.0 + k)).abs() < 1e-15);
    assert!((v[1].0 - k / (1.0 + k)).abs() < 1e-15);
    assert!((v[1].1 - 0.5 / (10.0 * root)).abs() < 1e-15);
}

/// A lightly damped second-order plant x'' = ω²(u − x) − 2ζωx', integrated finely.
fn residual_vibration(filter: Option<CommandFilter>) -> f64 {
    let (fn_hz, zeta) = (10.0, 0.02);
    let w = 2.0 * std::f64::consts::PI * fn_hz;
    let mut filter = filter;
    let (mut x, mut v) = (0.0f64, 0.0f64);
    let mut worst = 0.0f64;
    for tick in 0..3000u32 {
        let t = f64::from(tick) * PERIOD;
        // A 0.1 s constant-velocity move from 0 to 1.
        let planned = (t / 0.1).min(1.0);
        let u = filter.as_mut().map_or(planned, |f| f.next(planned));
        for _ in 0..20 {
            let dt = PERIOD / 20.0;
            v += (w * w * (u - x) - 2.0 * zeta * w * v) * dt;
            x += v * dt;
        }
        if t >= 0.5 {
            worst = worst.max((x - 1.0).abs());
        }
    }
    worst
}

#[test]
fn zv_shaper_leaves_far_less_vibration_on_a_lightly_damped_plant() {
    let plain = residual_vibration(None);
    let shaped = residual_vibration(Some(CommandFilter::Shaper(shaper(
        ShaperType::Zv,
        10.0,
        0.02,
    ))));
    assert!(plain > 0.01, "the plain move must ring: {plain}");
    assert!(shaped < plain / 20.0, "shaped {shaped} vs plain {plain}");
}

#[test]
fn filtered_move_ends_exactly_at_the_target() {
    let filters = [
        CommandFilter::Shaper(shaper(ShaperType::Zvd, 7.3, 0.05)),
        CommandFilter::Shaper(shaper(ShaperType::Ei, 300.0, 0.3)),
        CommandFilter::Notch(Notch::new(40.0, 1.0, PERIOD, 0.0).unwrap()),
    ];
    for mut f in filters {
        let target = 123.456_789;
        let mut out = 0.0;
        for tick in 0..5000u32 {
            let planned = (f64::from(tick) * PERIOD / 0.2).min(1.0) * target;
            out = f.next(planned);
        }
        assert!(f.is_settled());
        assert_eq!(out, target);
    }
}

#[test]
fn notch_removes_its_frequency() {
    let mut n = Notch::new(50.0, 1.0, PERIOD, 0.0).unwrap();
    let mut peak = 0.0f64;
    for tick in 0..4000u32 {
        let t = f64::from(tick) * PERIOD;
        let out = n.next((2.0 * std::f64::consts::PI * 50.0 * t).sin());
        if tick >= 2000 {
            peak = peak.max(out.abs());
        }
    }
    assert!(peak < 1e-6, "a 50 Hz input through a 50 Hz notch: {peak}");
}

#[test]
fn bad_parameters_are_typed_errors() {
    let name = |r: Result<Shaper, crate::error::EngineError>| match r {
        Err(crate::error::EngineError::InvalidArgument { name, .. }) => name,
        other => panic!("expected InvalidArgument, got {other:?}"),
    };
    let z = ShaperType::Zv;
    assert_eq!(name(Shaper::new(z, 0.0, 0.1, PERIOD, 0.0)), "frequency");
    assert_eq!(name(Shaper::new(z, -5.0, 0.1, PERIOD, 0.0)), "frequency");
    assert_eq!(
        name(Shaper::new(z, f64::NAN, 0.1, PERIOD, 0.0)),
        "frequency"
    );
    assert_eq!(name(Shaper::new(z, 600.0, 0.1, PERIOD, 0.0)), "frequency");
    assert_eq!(name(Shaper::new(z, 0.001, 0.1, PERIOD, 0.0)), "frequency");
    assert_eq!(name(Shaper::new(z, 5.0, 1.0, PERIOD, 0.0)), "damping");
    assert_eq!(name(Shaper::new(z, 5.0, -0.1, PERIOD, 0.0)), "damping");
    assert!(matches!(
        Notch::new(5.0, 0.0, PERIOD, 0.0),
        Err(crate::error::EngineError::InvalidArgument {
            name: "damping",
            ..
        })
    ));
    assert!(matches!(
        Notch::new(0.0, 1.0, PERIOD, 0.0),
        Err(crate::error::EngineError::InvalidArgument {
            name: "frequency",
            ..
        })
    ));
}

#[test]
fn filters_are_bit_identical_across_runs() {
    let run = || {
        let mut f = CommandFilter::Shaper(shaper(ShaperType::Zvd, 12.7, 0.13));
        let mut g = CommandFilter::Notch(Notch::new(33.0, 0.8, PERIOD, 0.0).unwrap());
        (0..2000u32)
            .map(|k| {
                let x = (f64::from(k) * 0.37).sin() * 10.0;
                (f.next(x).to_bits(), g.next(x).to_bits())
            })
            .collect::<Vec<_>>()
    };
    assert_eq!(run(), run());
}
