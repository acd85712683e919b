// Tests fail loudly.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

//! Every way a file can be refused names the file, the section and the key (where there is
//! one), and says why: one table row per error path of the parser.

use mcemu_canopen::eds::{Eds, Reason};

/// A small valid EDS: the mandatory objects, one RPDO, one TPDO, two CiA 402 objects.
const BASE: &str = "\
; base.eds: the smallest file the loader takes without warnings
[FileInfo]
FileName=base.eds
[DeviceInfo]
VendorNumber=0
NrOfRXPDO=1
NrOfTXPDO=1
BaudRate_1000=1
[DummyUsage]
Dummy0005=1
[MandatoryObjects]
SupportedObjects=3
1=0x1000
2=0x1001
3=0x1018
[OptionalObjects]
SupportedObjects=6
1=0x1400
2=0x1600
3=0x1800
4=0x1A00
5=0x6040
6=0x6041
[1000]
ParameterName=Device type
DataType=0x0007
AccessType=ro
DefaultValue=0x00020192
[1001]
ParameterName=Error register
DataType=0x0005
AccessType=ro
[1018]
ParameterName=Identity
ObjectType=0x9
SubNumber=2
[1018sub0]
ParameterName=Highest sub-index supported
DataType=0x0005
AccessType=ro
DefaultValue=1
[1018sub1]
ParameterName=Vendor-ID
DataType=0x0007
AccessType=ro
[1400]
ParameterName=RPDO1 communication
ObjectType=0x9
SubNumber=3
[1400sub0]
ParameterName=Highest sub-index supported
DataType=0x0005
AccessType=ro
DefaultValue=2
[1400sub1]
ParameterName=COB-ID
DataType=0x0007
AccessType=rw
DefaultValue=$NODEID+0x200
[1400sub2]
ParameterName=Transmission type
DataType=0x0005
AccessType=rw
DefaultValue=255
[1600]
ParameterName=RPDO1 mapping
ObjectType=0x9
SubNumber=3
[1600sub0]
ParameterName=Number of mapped objects
DataType=0x0005
AccessType=rw
DefaultValue=1
[1600sub1]
ParameterName=Mapped object 1
DataType=0x0007
AccessType=rw
DefaultValue=0x60400010
[1600sub2]
ParameterName=Mapped object 2
DataType=0x0007
AccessType=rw
DefaultValue=0
[1800]
ParameterName=TPDO1 communication
ObjectType=0x9
SubNumber=3
[1800sub0]
ParameterName=Highest sub-index supported
DataType=0x0005
AccessType=ro
DefaultValue=2
[1800sub1]
ParameterName=COB-ID
DataType=0x0007
AccessType=rw
DefaultValue=$NODEID+0x180
[1800sub2]
ParameterName=Transmission type
DataType=0x0005
AccessType=rw
DefaultValue=255
[1A00]
ParameterName=TPDO1 mapping
ObjectType=0x9
SubNumber=2
[1A00sub0]
ParameterName=Number of mapped objects
DataType=0x0005
AccessType=rw
DefaultValue=1
[1A00sub1]
ParameterName=Mapped object 1
DataType=0x0007
AccessType=rw
DefaultValue=0x60410010
[6040]
ParameterName=Controlword
DataType=0x0006
AccessType=rww
PDOMapping=1
[6041]
ParameterName=Statusword
DataType=0x0006
AccessType=ro
PDOMapping=1
";

/// `BASE` with `from` replaced by `to` (which must occur exactly once).
fn edit(from: &str, to: &str) -> String {
    assert_eq!(BASE.matches(from).count(), 1, "{from:?} must occur once");
    BASE.replacen(from, to, 1)
}

fn add(text: &str) -> String {
    format!("{BASE}{text}")
}

struct Case {
    what: &'static str,
    text: String,
    section: Option<&'static str>,
    key: Option<&'static str>,
    reason: fn(&Reason) -> bool,
}

fn case(
    what: &'static str,
    text: String,
    section: Option<&'static str>,
    key: Option<&'static str>,
    reason: fn(&Reason) -> bool,
) -> Case {
    Case {
        what,
        text,
        section,
        key,
        reason,
    }
}

#[test]
fn the_base_file_loads_cleanly() {
    let eds = Eds::parse("base.eds", BASE).unwrap();
    assert!(eds.warnings.is_empty(), "{:?}", eds.warnings);
    eds.dictionary(1).unwrap();
}

#[test]
fn every_error_names_file_section_and_key() {
    use Reason as R;
    let s = Some;
    let cases = vec![
        // ---- INI syntax ----
        case("not a key line", add("[2000]\nnonsense\n"), None, None, |r| matches!(r, R::Syntax(_))),
        case("unclosed section", add("[2000\n"), None, None, |r| *r == R::UnclosedSection),
        case("empty section", add("[]\n"), None, None, |r| *r == R::EmptySectionName),
        case("empty key", add("[2000]\n=1\n"), s("2000"), None, |r| *r == R::EmptyKey),
        case("key before any section", format!("a=b\n{BASE}"), None, None, |r| *r == R::KeyOutsideSection),
        case("duplicate section", add("[1000]\n"), s("1000"), None, |r| matches!(r, R::DuplicateSection { .. })),
        case("sub-index spelt twice", add("[1018sub01]\nParameterName=x\n"), s("1018sub01"), None, |r| matches!(r, R::DuplicateSection { .. })),
        case("duplicate key", edit("ParameterName=Controlword\n", "ParameterName=Controlword\nPARAMETERNAME=x\n"), s("6040"), s("PARAMETERNAME"), |r| matches!(r, R::DuplicateKey { .. })),
        // ---- descriptive sections ----
        case("bit rate flag", edit("BaudRate_1000=1", "BaudRate_1000=2"), s("DeviceInfo"), s("BaudRate_1000"), |r| matches!(r, R::NotABool { .. })),
        case("vendor number", edit("VendorNumber=0", "VendorNumber=acme"), s("DeviceInfo"), s("VendorNumber"), |r| matches!(r, R::NotANumber { .. })),
        case("vendor number range", edit("VendorNumber=0", "VendorNumber=0x100000000"), s("DeviceInfo"), s("VendorNumber"), |r| matches!(r, R::OutOfRangeFor { .. })),
        case("dummy usage flag", edit("Dummy0005=1", "Dummy0005=yes"), s("DummyUsage"), s("Dummy0005"), |r| matches!(r, R::NotABool { .. })),
        case("DCF node id", add("[DeviceComissioning]\nNodeID=0\n"), s("DeviceComissioning"), s("NodeID"), |r| matches!(r, R::OutOfRangeFor { .. })),
        case("DCF node id 128", add("[DeviceComissioning]\nNodeID=128\n"), s("DeviceComissioning"), s("NodeID"), |r| matches!(r, R::OutOfRangeFor { .. })),
        case("DCF bit rate", add("[DeviceCommissioning]\nBaudrate=300\n"), s("DeviceCommissioning"), s("Baudrate"), |r| matches!(r, R::OutOfRangeFor { .. })),
        // ---- object lists ----
        case("list without count", edit("SupportedObjects=6\n", ""), s("OptionalObjects"), s("SupportedObjects"), |r| *r == R::Missing),
        case("list entry missing", edit("SupportedObjects=6", "SupportedObjects=7"), s("OptionalObjects"), s("7"), |r| *r == R::Missing),
        case("list entry not a number", edit("6=0x6041", "6=0x60x1"), s("OptionalObjects"), s("6"), |r| matches!(r, R::NotANumber { .. })),
        case("listed object without section", edit("6=0x6041", "6=0x2000"), s("OptionalObjects"), s("6"), |r| *r == R::ListedObjectMissing { index: 0x2000 }),
        case("listed twice", edit("6=0x6041", "6=0x6040"), s("OptionalObjects"), s("6"), |r| *r == R::ListedTwice { index: 0x6040 }),
        case("listed index 0", edit("6=0x6041", "6=0"), s("OptionalObjects"), s("6"), |r| *r == R::IndexZero),
        case("mandatory object missing", edit("SupportedObjects=3\n1=0x1000\n2=0x1001\n3=0x1018", "SupportedObjects=2\n1=0x1000\n2=0x1001").replace("[1018", "[5018"), s("MandatoryObjects"), None, |r| *r == R::MandatoryObjectMissing { index: 0x1018 }),
        // ---- object sections ----
        case("object index 0", add("[0000]\nParameterName=x\n"), s("0000"), None, |r| *r == R::IndexZero),
        case("bad sub-index name", add("[1018subXYZ]\n"), s("1018subXYZ"), None, |r| *r == R::BadObjectSectionName),
        case("bad sub-index digits", add("[1018subG]\n"), s("1018subG"), None, |r| *r == R::BadObjectSectionName),
        case("sub-index without object", add("[2000sub1]\nParameterName=x\n"), s("2000sub1"), None, |r| *r == R::SubWithoutObject { index: 0x2000 }),
        case("sub-index of a VAR", add("[1000sub1]\nParameterName=x\n"), s("1000sub1"), None, |r| matches!(r, R::SubOfVar { index: 0x1000, .. })),
        case("no parameter name", edit("ParameterName=Controlword\n", ""), s("6040"), s("ParameterName"), |r| *r == R::Missing),
        case("no data type", edit("ParameterName=Statusword\nDataType=0x0006\n", "ParameterName=Statusword\n"), s("6041"), s("DataType"), |r| *r == R::Missing),
        case("no access type", edit("AccessType=rww\n", ""), s("6040"), s("AccessType"), |r| *r == R::Missing),
        case("unknown data type", edit("ParameterName=Controlword\nDataType=0x0006", "ParameterName=Controlword\nDataType=0x00ff"), s("6040"), s("DataType"), |r| *r == R::UnknownDataType { code: 0xFF }),
        case("unsupported data type", edit("ParameterName=Controlword\nDataType=0x0006", "ParameterName=Controlword\nDataType=0x0010"), s("6040"), s("DataType"), |r| matches!(r, R::UnsupportedDataType { code: 0x10, name: "INTEGER24" })),
        case("data type not a number", edit("ParameterName=Controlword\nDataType=0x0006", "ParameterName=Controlword\nDataType=UNSIGNED16"), s("6040"), s("DataType"), |r| matches!(r, R::NotANumber { .. })),
        case("unknown object type", edit("ParameterName=Identity\nObjectType=0x9", "ParameterName=Identity\nObjectType=0x3"), s("1018"), s("ObjectType"), |r| *r == R::UnknownObjectType { code: 3 }),
        case("unknown access type", edit("AccessType=rww", "AccessType=rx"), s("6040"), s("AccessType"), |r| matches!(r, R::UnknownAccessType { .. })),
        case("PDOMapping not 0/1", edit("AccessType=rww\nPDOMapping=1", "AccessType=rww\nPDOMapping=yes"), s("6040"), s("PDOMapping"), |r| matches!(r, R::NotABool { .. })),
        case("ObjFlags", edit("AccessType=rww\n", "AccessType=rww\nObjFlags=-1\n"), s("6040"), s("ObjFlags"), |r| matches!(r, R::OutOfRangeFor { .. })),
        case("SubNumber disagrees", edit("SubNumber=2\n[1018sub0]", "SubNumber=3\n[1018sub0]"), s("1018"), s("SubNumber"), |r| *r == R::SubNumberMismatch { declared: 3, found: 2 }),
        case("no sub-index 0", edit("[1018sub0]", "[1018sub2]"), s("1018"), None, |r| *r == R::NoSubIndexZero { index: 0x1018 }),
        case("no sub-indices at all", add("[2000]\nParameterName=x\nObjectType=0x8\n"), s("2000"), None, |r| *r == R::NoSubIndexZero { index: 0x2000 }),
        case("sub-index 0 not UNSIGNED8", edit("ParameterName=Highest sub-index supported\nDataType=0x0005\nAccessType=ro\nDefaultValue=1", "ParameterName=Highest sub-index supported\nDataType=0x0006\nAccessType=ro\nDefaultValue=1"), s("1018sub0"), s("DataType"), |r| matches!(r, R::SubIndexZeroType { .. })),
        case("compact and sub sections", add("[2000]\nParameterName=x\nObjectType=0x8\nDataType=0x0005\nAccessType=rw\nCompactSubObj=2\n[2000sub1]\nParameterName=y\n"), s("2000"), s("CompactSubObj"), |r| matches!(r, R::CompactWithSubs { .. })),
        case("compact name beyond count", add("[2000]\nParameterName=x\nObjectType=0x8\nDataType=0x0005\nAccessType=rw\nCompactSubObj=2\n[2000Name]\nNrOfEntries=1\n3=z\n"), s("2000Name"), s("3"), |r| *r == R::CompactEntryBeyond { entry: 3, count: 2 }),
        case("compact entry count", add("[2000]\nParameterName=x\nObjectType=0x8\nDataType=0x0005\nAccessType=rw\nCompactSubObj=2\n[2000Name]\nNrOfEntries=2\n1=z\n"), s("2000Name"), s("NrOfEntries"), |r| *r == R::EntryCountMismatch { declared: 2, found: 1 }),
        case("compact value key", add("[2000]\nParameterName=x\nObjectType=0x8\nDataType=0x0005\nAccessType=rw\nCompactSubObj=2\n[2000Value]\nfirst=1\n"), s("2000Value"), s("first"), |r| matches!(r, R::NotANumber { .. })),
        case("compact value", add("[2000]\nParameterName=x\nObjectType=0x8\nDataType=0x0005\nAccessType=rw\nCompactSubObj=2\n[2000Value]\n1=256\n"), s("2000Value"), s("1"), |r| matches!(r, R::OutOfRange { .. })),
        case("compact count", add("[2000]\nParameterName=x\nObjectType=0x8\nDataType=0x0005\nAccessType=rw\nCompactSubObj=255\n"), s("2000"), s("CompactSubObj"), |r| matches!(r, R::OutOfRangeFor { .. })),
        // ---- values ----
        case("default out of range", edit("AccessType=rww\n", "AccessType=rww\nDefaultValue=65536\n"), s("6040"), s("DefaultValue"), |r| matches!(r, R::OutOfRange { .. })),
        case("default not a number", edit("AccessType=rww\n", "AccessType=rww\nDefaultValue=0x12G\n"), s("6040"), s("DefaultValue"), |r| matches!(r, R::NotANumber { .. })),
        case("default bad octal", edit("AccessType=rww\n", "AccessType=rww\nDefaultValue=09\n"), s("6040"), s("DefaultValue"), |r| matches!(r, R::NotANumber { .. })),
        case("$NODEID out of range", edit("DefaultValue=$NODEID+0x200", "DefaultValue=$NODEID+0xFFFFFFFF"), s("1400sub1"), s("DefaultValue"), |r| matches!(r, R::NodeIdOutOfRange { node_id: 1, .. })),
        case("$NODEID malformed", edit("DefaultValue=$NODEID+0x200", "DefaultValue=$NODEID*2"), s("1400sub1"), s("DefaultValue"), |r| matches!(r, R::NotANumber { .. })),
        case("$NODEID in a real", add("[2000]\nParameterName=x\nDataType=0x0008\nAccessType=rw\nDefaultValue=$NODEID\n"), s("2000"), s("DefaultValue"), |r| matches!(r, R::NodeIdNotInteger { .. })),
        case("boolean default", add("[2000]\nParameterName=x\nDataType=0x0001\nAccessType=rw\nDefaultValue=2\n"), s("2000"), s("DefaultValue"), |r| matches!(r, R::NotABool { .. })),
        case("real default", add("[2000]\nParameterName=x\nDataType=0x0011\nAccessType=rw\nDefaultValue=1,5\n"), s("2000"), s("DefaultValue"), |r| matches!(r, R::NotANumber { .. })),
        case("string not ASCII", add("[2000]\nParameterName=x\nDataType=0x0009\nAccessType=ro\nDefaultValue=Gr\u{f6}\u{df}e\n"), s("2000"), s("DefaultValue"), |r| matches!(r, R::NotVisibleString { .. })),
        case("octets not hex", add("[2000]\nParameterName=x\nDataType=0x000A\nAccessType=ro\nDefaultValue=0x123\n"), s("2000"), s("DefaultValue"), |r| matches!(r, R::NotHexBytes { .. })),
        case("limits on a string", add("[2000]\nParameterName=x\nDataType=0x0009\nAccessType=ro\nLowLimit=a\n"), s("2000"), s("LowLimit"), |r| matches!(r, R::LimitsNotNumeric { .. })),
        case("limit not a number", edit("AccessType=rww\n", "AccessType=rww\nHighLimit=max\n"), s("6040"), s("HighLimit"), |r| matches!(r, R::NotANumber { .. })),
        case("limits crossed", edit("AccessType=rww\n", "AccessType=rww\nLowLimit=10\nHighLimit=5\n"), s("6040"), s("HighLimit"), |r| matches!(r, R::LimitsCrossed { .. })),
        case("default below low limit", edit("AccessType=rww\n", "AccessType=rww\nLowLimit=1\nDefaultValue=0\n"), s("6040"), s("DefaultValue"), |r| matches!(r, R::BelowLowLimit { .. })),
        case("no default, zero below low limit", edit("AccessType=rww\n", "AccessType=rww\nLowLimit=1\n"), s("6040"), s("DefaultValue"), |r| matches!(r, R::BelowLowLimit { .. })),
        case("default above high limit", edit("AccessType=rww\n", "AccessType=rww\nDefaultValue=9\nHighLimit=8\n"), s("6040"), s("DefaultValue"), |r| matches!(r, R::AboveHighLimit { .. })),
        case("DCF value above high limit", edit("AccessType=rww\n", "AccessType=rww\nHighLimit=8\nParameterValue=9\n"), s("6040"), s("ParameterValue"), |r| matches!(r, R::AboveHighLimit { .. })),
        case("$NODEID default above limit", edit("DefaultValue=$NODEID+0x200", "DefaultValue=$NODEID+0x200\nHighLimit=0x240"), s("1400sub1"), s("DefaultValue"), |r| matches!(r, R::AboveHighLimit { .. })),
        // ---- PDOs ----
        case("maps a missing object", edit("DefaultValue=0x60400010", "DefaultValue=0x60420010"), s("1600sub1"), s("DefaultValue"), |r| matches!(r, R::Pdo(m) if m.contains("no such object"))),
        case("maps a non-mappable object", edit("DefaultValue=0x60400010", "DefaultValue=0x10010008"), s("1600sub1"), s("DefaultValue"), |r| matches!(r, R::Pdo(m) if m.contains("not PDO-mappable"))),
        case("maps ro into an RPDO", edit("DefaultValue=0x60400010", "DefaultValue=0x60410010"), s("1600sub1"), s("DefaultValue"), |r| matches!(r, R::Pdo(m) if m.contains("AccessType=ro"))),
        case("maps rww into a TPDO", edit("DefaultValue=0x60410010", "DefaultValue=0x60400010"), s("1A00sub1"), s("DefaultValue"), |r| matches!(r, R::Pdo(m) if m.contains("AccessType=rww"))),
        case("wrong length", edit("DefaultValue=0x60400010", "DefaultValue=0x60400020"), s("1600sub1"), s("DefaultValue"), |r| matches!(r, R::Pdo(m) if m.contains("has 16 bits"))),
        case("more than 64 bits", edit("AccessType=rw\nDefaultValue=1\n[1600sub1]", "AccessType=rw\nDefaultValue=2\n[1600sub1]").replace("ParameterName=Mapped object 2\nDataType=0x0007\nAccessType=rw\nDefaultValue=0", "ParameterName=Mapped object 2\nDataType=0x0007\nAccessType=rw\nDefaultValue=0x20000040") + "[2000]\nParameterName=wide\nDataType=0x001B\nAccessType=rww\nPDOMapping=1\n", s("1600sub2"), s("DefaultValue"), |r| matches!(r, R::Pdo(m) if m.contains("would carry 80 bits"))),
        case("dummy not declared", edit("DefaultValue=0x60400010", "DefaultValue=0x00060010"), s("1600sub1"), s("DefaultValue"), |r| matches!(r, R::Pdo(m) if m.contains("Dummy0006"))),
        case("count beyond entries", edit("AccessType=rw\nDefaultValue=1\n[1A00sub1]", "AccessType=rw\nDefaultValue=2\n[1A00sub1]"), s("1A00sub0"), s("DefaultValue"), |r| matches!(r, R::Pdo(m) if m.contains("sub-index 2 does not exist"))),
        case("mapping without communication", add("[1A01]\nParameterName=m\nObjectType=0x9\n[1A01sub0]\nParameterName=n\nDataType=0x0005\nAccessType=rw\nDefaultValue=0\n"), s("1A01"), None, |r| matches!(r, R::Pdo(m) if m.contains("without its communication object 0x1801"))),
        case("communication without mapping", add("[1401]\nParameterName=RPDO2\nObjectType=0x9\n[1401sub0]\nParameterName=n\nDataType=0x0005\nAccessType=ro\nDefaultValue=2\n"), s("1401"), None, |r| matches!(r, R::Pdo(m) if m.contains("no mapping object [1601]"))),
        case("COB-ID of the wrong type", edit("ParameterName=COB-ID\nDataType=0x0007\nAccessType=rw\nDefaultValue=$NODEID+0x180", "ParameterName=COB-ID\nDataType=0x0006\nAccessType=rw\nDefaultValue=$NODEID+0x180"), s("1800sub1"), s("DataType"), |r| matches!(r, R::Pdo(m) if m.contains("UNSIGNED32"))),
        case("no COB-ID", edit("[1800sub1]\nParameterName=COB-ID\nDataType=0x0007\nAccessType=rw\nDefaultValue=$NODEID+0x180\n", "").replace("SubNumber=3\n[1800sub0]", "SubNumber=2\n[1800sub0]"), s("1800"), None, |r| matches!(r, R::Pdo(m) if m.contains("no COB-ID"))),
    ];
    let mut failures = Vec::new();
    for c in &cases {
        let err = match Eds::parse("base.eds", &c.text) {
            Ok(_) => {
                failures.push(format!("{}: loaded", c.what));
                continue;
            }
            Err(err) => err,
        };
        let shown = err.to_string();
        let mut prefix = "base.eds: ".to_string();
        if let Some(section) = c.section {
            prefix += &format!("[{section}] ");
        }
        if let Some(key) = c.key {
            prefix += &format!("{key}: ");
        }
        if &*err.file != "base.eds"
            || err.section.as_deref() != c.section
            || err.key.as_deref() != c.key
            || !(c.reason)(&err.reason)
            || !shown.starts_with(&prefix)
        {
            failures.push(format!("{}: got {shown:?} ({err:?})", c.what));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn the_documented_example_message() {
    let text = edit(
        "ParameterName=Controlword\nDataType=0x0006",
        "ParameterName=Controlword\nDataType=0x00ff",
    );
    let err = Eds::parse("cia402-drive.eds", &text).unwrap_err();
    let line = text.lines().position(|l| l == "DataType=0x00ff").unwrap() + 1;
    assert_eq!(
        err.to_string(),
        format!("cia402-drive.eds: [6040] DataType: unknown data type 0x00ff (line {line})")
    );
}

#[test]
fn io_errors_and_oversized_files_name_the_path() {
    let err = Eds::load("/nonexistent/drive.eds").unwrap_err();
    assert_eq!(&*err.file, "/nonexistent/drive.eds");
    assert!(matches!(err.reason, Reason::Io(_)), "{err}");

    let dir = std::env::temp_dir().join(format!("mcemu-eds-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let big = dir.join("big.eds");
    let mut text = BASE.to_string();
    let padding = format!("; {}\n", "x".repeat(1000));
    while text.len() <= Eds::MAX_FILE_SIZE {
        text += &padding;
    }
    std::fs::write(&big, &text).unwrap();
    let err = Eds::load(&big).unwrap_err();
    std::fs::remove_dir_all(&dir).unwrap();
    assert!(matches!(err.reason, Reason::TooLarge { .. }), "{err}");
    assert!(err.to_string().contains("big.eds: the file has"));
}

#[test]
fn node_ids_outside_1_to_127_are_refused() {
    let eds = Eds::parse("base.eds", BASE).unwrap();
    for node_id in [0, 128, 255] {
        let err = eds.dictionary(node_id).unwrap_err();
        assert_eq!(
            err.reason,
            Reason::NodeIdInvalid {
                node_id: u32::from(node_id)
            }
        );
        assert!(eds.default_pdos(node_id).is_err());
        assert!(eds.entry_defs(node_id).is_err());
    }
}
