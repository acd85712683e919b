//! The JSON of every coupling command (issue 12 items 1, 2 and 10), pinned as `command_json.rs`
//! pins the others: each variant with every field set serializes to a literal and back, and
//! the form with only the required fields reads back with its defaults (commanded master, no
//! clutch, linear table, relative single cam started at once, scalings 1).
#![allow(clippy::unwrap_used)]

mod common;

use axes::command::{
    CamIn, CamInterpolation, CamOut, CamPoint, CamTableDefine, Command, Direction, FollowSegment,
    GearIn, GearOut, GearSetRatio, MasterSource,
};

fn full() -> Vec<(Command, &'static str)> {
    vec![
        (
            Command::from(GearIn {
                master: 1,
                slave: 0,
                numerator: 4.0,
                denominator: 5.0,
                master_source: MasterSource::Encoder,
                clutch_distance: Some(2000.0),
                acceleration: None,
                direction: Some(Direction::Negative),
                phase_offset: 7,
                transition: false,
            }),
            r#"{"type":"gear_in","master":1,"slave":0,"numerator":4.0,"denominator":5.0,"master_source":"encoder","clutch_distance":2000.0,"direction":"negative","phase_offset":7}"#,
        ),
        (
            Command::from(GearIn {
                master: 0,
                slave: 1,
                numerator: 1.0,
                denominator: 2.0,
                master_source: MasterSource::Commanded,
                clutch_distance: None,
                acceleration: None,
                direction: None,
                phase_offset: 0,
                transition: true,
            }),
            r#"{"type":"gear_in","master":0,"slave":1,"numerator":1.0,"denominator":2.0,"master_source":"commanded","transition":true}"#,
        ),
        (
            Command::from(GearSetRatio {
                slave: 2,
                numerator: -1.0,
                denominator: 3.0,
            }),
            r#"{"type":"gear_set_ratio","slave":2,"numerator":-1.0,"denominator":3.0}"#,
        ),
        (
            Command::from(GearOut { slave: 2 }),
            r#"{"type":"gear_out","slave":2}"#,
        ),
        (
            Command::from(CamTableDefine {
                table: 7,
                points: vec![
                    CamPoint {
                        master: 0.0,
                        slave: 0.0,
                        segment: FollowSegment::Normal,
                    },
                    CamPoint {
                        master: 10.0,
                        slave: 5.0,
                        segment: FollowSegment::Stop,
                    },
                ],
                interpolation: CamInterpolation::Follow,
            }),
            r#"{"type":"cam_table","table":7,"points":[{"master":0.0,"slave":0.0},{"master":10.0,"slave":5.0,"segment":"stop"}],"interpolation":"follow"}"#,
        ),
        (
            Command::from(CamIn {
                master: 0,
                slave: 1,
                table: 7,
                master_source: MasterSource::Actual,
                periodic: true,
                loop_count: 3,
                master_absolute: true,
                slave_absolute: true,
                master_offset: 1.5,
                slave_offset: -2.0,
                master_scaling: 2.0,
                slave_scaling: 0.5,
                start_position: Some(50000.0),
                start_direction: Some(Direction::Positive),
                start_input: None,
                start_capture: None,
            }),
            r#"{"type":"cam_in","master":0,"slave":1,"table":7,"master_source":"actual","periodic":true,"loop_count":3,"master_absolute":true,"slave_absolute":true,"master_offset":1.5,"slave_offset":-2.0,"master_scaling":2.0,"slave_scaling":0.5,"start_position":50000.0,"start_direction":"positive"}"#,
        ),
        (
            Command::from(CamOut { slave: 1 }),
            r#"{"type":"cam_out","slave":1}"#,
        ),
    ]
}

#[test]
fn every_coupling_command_serializes_to_its_pinned_json_and_back() {
    let cases = full();
    // One case per coupling command, and gear_in's transition switch (HMC) on its own.
    assert_eq!(cases.len(), 7, "one case per coupling command");
    common::assert_pinned(cases);
}

#[test]
fn the_required_fields_alone_read_back_with_their_defaults() {
    let g: Command = serde_json::from_str(
        r#"{"type":"gear_in","master":0,"slave":1,"numerator":1,"denominator":2}"#,
    )
    .unwrap();
    assert_eq!(
        g,
        Command::from(GearIn {
            master: 0,
            slave: 1,
            numerator: 1.0,
            denominator: 2.0,
            master_source: MasterSource::Commanded,
            clutch_distance: None,
            acceleration: None,
            direction: None,
            phase_offset: 0,
            transition: false,
        })
    );
    let t: Command = serde_json::from_str(
        r#"{"type":"cam_table","table":0,"points":[{"master":0,"slave":0},{"master":1,"slave":1}]}"#,
    )
    .unwrap();
    let Command::Coupling(axes::command::CouplingCommand::CamTable(t)) = t else {
        panic!("{t:?}")
    };
    assert_eq!(t.interpolation, CamInterpolation::Linear);
    let c: Command =
        serde_json::from_str(r#"{"type":"cam_in","master":0,"slave":1,"table":0}"#).unwrap();
    assert_eq!(
        serde_json::to_string(&c).unwrap(),
        r#"{"type":"cam_in","master":0,"slave":1,"table":0,"master_source":"commanded"}"#
    );
}

#[test]
fn coupling_serde_errors_name_the_field() {
    for (json, message) in [
        (
            r#"{"type":"gear_in","master":0,"slave":1,"numerator":1,"denominator":2,"ratio":3}"#,
            "unknown field `ratio`",
        ),
        (
            r#"{"type":"gear_in","master":0,"slave":1,"numerator":1}"#,
            "missing field `denominator`",
        ),
        (
            r#"{"type":"gear_in","master":0,"slave":1,"numerator":1,"denominator":2,"master_source":"psychic"}"#,
            "unknown variant `psychic`, expected one of `commanded`, `actual`, `encoder`",
        ),
        (
            r#"{"type":"cam_table","table":0,"points":[],"interpolation":"quintic"}"#,
            "unknown variant `quintic`, expected one of `linear`, `cubic`, `follow`",
        ),
    ] {
        let e = serde_json::from_str::<Command>(json)
            .unwrap_err()
            .to_string();
        assert!(e.starts_with(message), "{json}: {e}");
    }
}
