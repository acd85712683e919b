//! The descriptive sections of a CiA 306 file: [FileInfo], [DeviceInfo], [DummyUsage],
//! [Comments] and, in a DCF, [DeviceComissioning].

use super::error::EdsError;
use super::fields::Fields;
use super::ini::Section;

/// [FileInfo], as written (CiA 306 gives these no meaning a device needs).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct FileInfo {
    pub file_name: Option<String>,
    pub file_version: Option<String>,
    pub file_revision: Option<String>,
    pub eds_version: Option<String>,
    pub description: Option<String>,
    pub created_by: Option<String>,
    pub creation_date: Option<String>,
    pub creation_time: Option<String>,
    pub modified_by: Option<String>,
    pub modification_date: Option<String>,
    pub modification_time: Option<String>,
}

impl FileInfo {
    pub(crate) fn read(fields: Fields<'_, '_>) -> FileInfo {
        let text = |key| fields.text(key).map(str::to_string);
        FileInfo {
            file_name: text("FileName"),
            file_version: text("FileVersion"),
            file_revision: text("FileRevision"),
            eds_version: text("EDSVersion"),
            description: text("Description"),
            created_by: text("CreatedBy"),
            creation_date: text("CreationDate"),
            creation_time: text("CreationTime"),
            modified_by: text("ModifiedBy"),
            modification_date: text("ModificationDate"),
            modification_time: text("ModificationTime"),
        }
    }
}

/// The CiA 301 bit rates an EDS can declare (`BaudRate_<kbit/s>=1`).
pub const BIT_RATES_KBIT: [u16; 8] = [10, 20, 50, 125, 250, 500, 800, 1000];

/// [DeviceInfo]: identity and communication capabilities.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct DeviceInfo {
    pub vendor_name: Option<String>,
    pub vendor_number: Option<u32>,
    pub product_name: Option<String>,
    pub product_number: Option<u32>,
    pub revision_number: Option<u32>,
    pub order_code: Option<String>,
    /// Supported bit rates in kbit/s, ascending.
    pub bit_rates_kbit: Vec<u16>,
    pub simple_boot_up_master: bool,
    pub simple_boot_up_slave: bool,
    /// Mapping granularity in bits (8: byte-aligned PDO mapping; 0: no mapping).
    pub granularity: Option<u8>,
    pub dynamic_channels_supported: u8,
    pub group_messaging: bool,
    pub nr_of_rx_pdo: u16,
    pub nr_of_tx_pdo: u16,
    pub lss_supported: bool,
    pub compact_pdo: u8,
}

impl DeviceInfo {
    pub(crate) fn read(f: Fields<'_, '_>) -> Result<DeviceInfo, EdsError> {
        let text = |key| f.text(key).map(str::to_string);
        let mut bit_rates_kbit = Vec::new();
        for rate in BIT_RATES_KBIT {
            if f.flag(&format!("BaudRate_{rate}"))?.unwrap_or(false) {
                bit_rates_kbit.push(rate);
            }
        }
        Ok(DeviceInfo {
            vendor_name: text("VendorName"),
            vendor_number: f.unsigned("VendorNumber", "UNSIGNED32")?,
            product_name: text("ProductName"),
            product_number: f.unsigned("ProductNumber", "UNSIGNED32")?,
            revision_number: f.unsigned("RevisionNumber", "UNSIGNED32")?,
            order_code: text("OrderCode"),
            bit_rates_kbit,
            simple_boot_up_master: f.flag("SimpleBootUpMaster")?.unwrap_or(false),
            simple_boot_up_slave: f.flag("SimpleBootUpSlave")?.unwrap_or(false),
            granularity: f.unsigned("Granularity", "0–64")?,
            dynamic_channels_supported: f
                .unsigned("DynamicChannelsSupported", "0–255")?
                .unwrap_or(0),
            group_messaging: f.flag("GroupMessaging")?.unwrap_or(false),
            nr_of_rx_pdo: f.unsigned("NrOfRXPDO", "0–512")?.unwrap_or(0),
            nr_of_tx_pdo: f.unsigned("NrOfTXPDO", "0–512")?.unwrap_or(0),
            lss_supported: f.flag("LSS_Supported")?.unwrap_or(false),
            compact_pdo: f.unsigned("CompactPDO", "0–255")?.unwrap_or(0),
        })
    }
}

/// [DummyUsage]: which data types (codes 1–7) may be mapped as dummy entries (mapping index =
/// the data type code) to skip bytes of a received PDO.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct DummyUsage {
    /// `supported[code]` for codes 1–7; `[0]` is unused.
    pub supported: [bool; 8],
}

impl DummyUsage {
    pub(crate) fn read(f: Fields<'_, '_>) -> Result<DummyUsage, EdsError> {
        let mut usage = DummyUsage::default();
        for (code, slot) in usage.supported.iter_mut().enumerate().skip(1) {
            *slot = f.flag(&format!("Dummy{code:04}"))?.unwrap_or(false);
        }
        Ok(usage)
    }

    /// Whether mapping index `index` (sub-index 0) is a dummy entry this device accepts.
    pub fn supports(&self, index: u16) -> bool {
        self.supported
            .get(usize::from(index))
            .copied()
            .unwrap_or(false)
    }
}

/// [DeviceComissioning] of a DCF (CiA 306 spells it with one "m"; the correct spelling is read
/// too): the node this configuration is for.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Commissioning {
    pub node_id: Option<u8>,
    pub node_name: Option<String>,
    /// Bit rate in kbit/s.
    pub bit_rate_kbit: Option<u16>,
    pub net_number: Option<u32>,
    pub network_name: Option<String>,
    pub canopen_manager: bool,
    pub lss_serial_number: Option<u32>,
}

impl Commissioning {
    pub(crate) fn read(f: Fields<'_, '_>) -> Result<Commissioning, EdsError> {
        let text = |key| f.text(key).map(str::to_string);
        let node_id = f.unsigned::<u8>("NodeID", "1–127")?;
        if let (Some(id), Some(item)) = (node_id, f.item("NodeID")) {
            if !(1..=127).contains(&id) {
                return Err(f.error(
                    item,
                    super::error::Reason::OutOfRangeFor {
                        text: item.value.to_string(),
                        range: "1–127",
                    },
                ));
            }
        }
        let bit_rate_kbit = f.unsigned::<u16>("Baudrate", "a CiA 301 bit rate")?;
        if let (Some(rate), Some(item)) = (bit_rate_kbit, f.item("Baudrate")) {
            if !BIT_RATES_KBIT.contains(&rate) {
                return Err(f.error(
                    item,
                    super::error::Reason::OutOfRangeFor {
                        text: item.value.to_string(),
                        range: "10, 20, 50, 125, 250, 500, 800 or 1000 kbit/s",
                    },
                ));
            }
        }
        Ok(Commissioning {
            node_id,
            node_name: text("NodeName"),
            bit_rate_kbit,
            net_number: f.unsigned("NetNumber", "UNSIGNED32")?,
            network_name: text("NetworkName"),
            canopen_manager: f.flag("CANopenManager")?.unwrap_or(false),
            lss_serial_number: f.unsigned("LSS_SerialNumber", "UNSIGNED32")?,
        })
    }
}

/// [Comments]: `Lines=n`, `Line1=` … `Line<n>=`.
pub(crate) fn read_comments(section: &Section<'_>) -> Vec<String> {
    (1..=section.items.len())
        .map_while(|n| section.get(&format!("line{n}")))
        .map(|item| item.value.to_string())
        .collect()
}
