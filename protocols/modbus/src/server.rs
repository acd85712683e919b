//! The transport-independent request handler: a unit id and a request PDU in, a response PDU
//! (or nothing) out. It owns unit filtering and broadcast, listen-only mode, FC 8, FC 17 and
//! FC 43/14, fault injection (`no_reply`, `exception`, `delay`) and counting; everything else
//! goes to the [`DataModel`].
//!
//! Check order (anchors §26 item 1; Modbus Application Protocol V1.1b3 §7 figure 20): unit →
//! function code supported (01) → quantity and values (03, in `pdu::decode_request`) →
//! address (02, in the model) → execution (04, in the model).

use std::sync::Arc;

use crate::frame::rtu::BROADCAST;
use crate::model::{DataModel, DeviceIdentity, Peer, RequestContext};
use crate::pdu::{self, fc, limits::MAX_PDU, Exception, Request, Response};
use crate::state::FrontendState;

/// What to send back.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// A response PDU, to frame with the request's unit id (and transaction id on TCP).
    Reply(Vec<u8>),
    /// Nothing: a broadcast, another unit on an RTU line, listen-only mode, a `no_reply` fault.
    Silent,
    /// Nothing, and the connection is to be closed: a `close` fault.
    Close,
}

/// A model and the front-end state it is served with.
pub struct Server<D> {
    model: Arc<D>,
    state: Arc<FrontendState>,
}

impl<D> Clone for Server<D> {
    fn clone(&self) -> Self {
        Server {
            model: Arc::clone(&self.model),
            state: Arc::clone(&self.state),
        }
    }
}

/// FC 8 sub-functions (Modbus Application Protocol V1.1b3 §6.8.1).
mod sub {
    pub const RETURN_QUERY_DATA: u16 = 0x00;
    pub const RESTART_COMMUNICATIONS: u16 = 0x01;
    pub const FORCE_LISTEN_ONLY: u16 = 0x04;
    pub const CLEAR_COUNTERS: u16 = 0x0A;
    /// 0x0B bus message … 0x12 bus character overrun.
    pub const FIRST_COUNTER: u16 = 0x0B;
    pub const LAST_COUNTER: u16 = 0x12;
}

impl<D: DataModel> Server<D> {
    pub fn new(model: Arc<D>, state: Arc<FrontendState>) -> Server<D> {
        Server { model, state }
    }

    pub fn state(&self) -> &Arc<FrontendState> {
        &self.state
    }

    pub fn model(&self) -> &Arc<D> {
        &self.model
    }

    /// Handle one request PDU addressed to `unit`. Framing (RTU or TCP) comes from the state.
    pub async fn handle(&self, unit: u8, pdu: &[u8], peer: &Peer) -> Outcome {
        let state = &*self.state;
        let c = &state.counters;
        c.diagnostics.bus_message.inc();
        let rtu = state.framing().is_rtu();
        let broadcast = rtu && unit == BROADCAST;
        let function = pdu.first().copied().unwrap_or(0);
        if !broadcast && !self.model.serves(unit) {
            if rtu {
                // Serial Line V1.02 §2.2: a slave ignores frames for other addresses.
                c.other_unit.inc();
                return Outcome::Silent;
            }
            // Messaging on TCP/IP Implementation Guide V1.0b §4.4.2: a gateway whose target
            // does not answer returns 0x0B.
            c.diagnostics.server_message.inc();
            c.request(function);
            return self
                .reply(Response::exception(
                    function,
                    Exception::GatewayTargetFailed,
                ))
                .await;
        }
        c.diagnostics.server_message.inc();
        c.request(function);
        if broadcast {
            c.broadcasts.inc();
        }
        if state.listen_only() {
            // §6.8.1 sub-function 04: messages are monitored, nothing is executed or answered
            // except Restart Communications (01), which leaves the mode, still unanswered.
            if let Ok(Request::Diagnostics {
                sub_function: sub::RESTART_COMMUNICATIONS,
                data,
            }) = pdu::decode_request(pdu)
            {
                if restart_data_valid(data) {
                    self.restart_communications();
                }
            }
            return self.no_response();
        }
        if broadcast {
            return self.broadcast(pdu, peer).await;
        }
        if state.faults.take_no_reply(&c.faults_applied) {
            return self.no_response();
        }
        if state.faults.take_close(&c.faults_applied) {
            let _ = self.no_response();
            return Outcome::Close;
        }
        let response = match pdu::decode_request(pdu) {
            Err(refusal) => Response::from(refusal),
            Ok(request) => {
                let forced = state.faults.take_exception(
                    request.function(),
                    |a| covers(&request, a),
                    &c.faults_applied,
                );
                match forced {
                    Some(e) => Response::exception(request.function(), e),
                    None => match self.respond(unit, false, &request, peer).await {
                        Some(r) => r,
                        None => return self.no_response(),
                    },
                }
            }
        };
        self.reply(response).await
    }

    /// Serial Line V1.02 §2.1: a broadcast is a write that every slave executes and none
    /// answers, not even with an exception. Reads are ignored. Of FC 8, the sub-functions that
    /// change state (01, 04, 0A) are executed.
    async fn broadcast(&self, pdu: &[u8], peer: &Peer) -> Outcome {
        let c = &self.state.counters;
        match pdu::decode_request(pdu) {
            Ok(request)
                if request.is_write()
                    || matches!(
                        request,
                        Request::Diagnostics {
                            sub_function: sub::RESTART_COMMUNICATIONS
                                | sub::FORCE_LISTEN_ONLY
                                | sub::CLEAR_COUNTERS,
                            ..
                        }
                    ) =>
            {
                if let Some(Response::Exception { exception, .. }) =
                    self.respond(BROADCAST, true, &request, peer).await
                {
                    // Counted (Serial Line §6.1.1 counter 3 includes broadcasts), never sent.
                    c.exception(exception);
                }
            }
            Ok(_) => {}
            Err(refusal) => c.exception(refusal.exception),
        }
        self.no_response()
    }

    /// The response to a decoded request, or `None` for no response (FC 8 sub-function 04).
    async fn respond(
        &self,
        unit: u8,
        broadcast: bool,
        request: &Request<'_>,
        peer: &Peer,
    ) -> Option<Response> {
        match request {
            Request::Diagnostics { sub_function, data } => self.diagnostics(*sub_function, data),
            Request::ReportServerId => Some(match self.model.identity(unit) {
                Some(identity) => report_server_id(identity),
                None => Response::exception(fc::REPORT_SERVER_ID, Exception::IllegalFunction),
            }),
            Request::ReadDeviceIdentification {
                read_code,
                object_id,
            } => Some(match self.model.identity(unit) {
                Some(identity) => device_identification(identity, *read_code, *object_id),
                None => Response::exception(fc::ENCAPSULATED_INTERFACE, Exception::IllegalFunction),
            }),
            _ => {
                let context = RequestContext {
                    unit,
                    broadcast,
                    peer: peer.clone(),
                };
                Some(match self.model.execute(&context, request).await {
                    Ok(response) => response,
                    Err(e) => {
                        if e.exception == Exception::ServerDeviceFailure {
                            tracing::warn!(
                                peer = %peer,
                                unit,
                                function = request.function(),
                                address = ?first_address(request),
                                reason = %e.reason,
                                "modbus request refused by the engine"
                            );
                            self.state.record_error(
                                peer,
                                unit,
                                request.function(),
                                e.exception,
                                &e.reason,
                            );
                        }
                        Response::exception(request.function(), e.exception)
                    }
                })
            }
        }
    }

    /// FC 8 (Modbus Application Protocol V1.1b3 §6.8.1; counters: Serial Line V1.02 §6.1.1).
    /// Every sub-function but 00 takes the two data bytes the specification gives (0000, or
    /// FF00 for 01); anything else is exception 03.
    fn diagnostics(&self, sub_function: u16, data: &[u8]) -> Option<Response> {
        let diag = &self.state.counters.diagnostics;
        let echo = || Response::Diagnostics {
            sub_function,
            data: data.to_vec(),
        };
        let bad_value = || Response::exception(fc::DIAGNOSTICS, Exception::IllegalDataValue);
        let zero = data == [0, 0];
        match sub_function {
            sub::RETURN_QUERY_DATA => Some(echo()),
            sub::RESTART_COMMUNICATIONS => {
                if !restart_data_valid(data) {
                    return Some(bad_value());
                }
                // The response goes out "before the restart is executed"; nothing observable
                // differs if the counters are cleared first.
                self.restart_communications();
                Some(echo())
            }
            sub::FORCE_LISTEN_ONLY if zero => {
                self.state.set_listen_only(true);
                None
            }
            sub::CLEAR_COUNTERS if zero => {
                diag.clear();
                Some(echo())
            }
            sub::FIRST_COUNTER..=sub::LAST_COUNTER if zero => {
                // The specification's counters are 16-bit: they wrap.
                let n = diag.by_sub_function(sub_function).map_or(0, |c| c.get()) as u16;
                Some(Response::Diagnostics {
                    sub_function,
                    data: n.to_be_bytes().to_vec(),
                })
            }
            sub::FORCE_LISTEN_ONLY
            | sub::CLEAR_COUNTERS
            | sub::FIRST_COUNTER..=sub::LAST_COUNTER => Some(bad_value()),
            _ => Some(Response::exception(
                fc::DIAGNOSTICS,
                Exception::IllegalFunction,
            )),
        }
    }

    /// Sub-function 01: counters cleared, listen-only mode left.
    fn restart_communications(&self) {
        self.state.counters.diagnostics.clear();
        self.state.set_listen_only(false);
    }

    fn no_response(&self) -> Outcome {
        let c = &self.state.counters;
        c.no_response.inc();
        c.diagnostics.server_no_response.inc();
        Outcome::Silent
    }

    async fn reply(&self, response: Response) -> Outcome {
        let c = &self.state.counters;
        if let Response::Exception { exception, .. } = response {
            c.exception(exception);
        }
        let mut out = Vec::with_capacity(32);
        pdu::encode_response(&response, &mut out);
        if let Some(delay) = self.state.faults.take_delay(&c.faults_applied) {
            tokio::time::sleep(delay).await;
        }
        c.replies.inc();
        Outcome::Reply(out)
    }
}

fn restart_data_valid(data: &[u8]) -> bool {
    // 0000 leaves the communication event log, FF00 clears it too; this server keeps no log.
    data == [0, 0] || data == [0xFF, 0]
}

/// Whether `request` reads or writes `address` (for `exception` faults with an address).
fn covers(request: &Request<'_>, address: u16) -> bool {
    let within = |start: u16, quantity: u16| {
        let (a, s) = (u32::from(address), u32::from(start));
        a >= s && a < s + u32::from(quantity)
    };
    match request {
        Request::ReadCoils { address, quantity }
        | Request::ReadDiscreteInputs { address, quantity }
        | Request::ReadHoldingRegisters { address, quantity }
        | Request::ReadInputRegisters { address, quantity }
        | Request::WriteMultipleCoils {
            address, quantity, ..
        }
        | Request::WriteMultipleRegisters {
            address, quantity, ..
        } => within(*address, *quantity),
        Request::WriteSingleCoil { address: a, .. }
        | Request::WriteSingleRegister { address: a, .. }
        | Request::MaskWriteRegister { address: a, .. } => *a == address,
        Request::ReadWriteMultipleRegisters {
            read_address,
            read_quantity,
            write_address,
            write_quantity,
            ..
        } => within(*read_address, *read_quantity) || within(*write_address, *write_quantity),
        Request::Diagnostics { .. }
        | Request::ReportServerId
        | Request::ReadDeviceIdentification { .. } => false,
    }
}

/// The first address a request touches, for logs.
fn first_address(request: &Request<'_>) -> Option<u16> {
    match request {
        Request::ReadCoils { address, .. }
        | Request::ReadDiscreteInputs { address, .. }
        | Request::ReadHoldingRegisters { address, .. }
        | Request::ReadInputRegisters { address, .. }
        | Request::WriteSingleCoil { address, .. }
        | Request::WriteSingleRegister { address, .. }
        | Request::WriteMultipleCoils { address, .. }
        | Request::WriteMultipleRegisters { address, .. }
        | Request::MaskWriteRegister { address, .. } => Some(*address),
        Request::ReadWriteMultipleRegisters { write_address, .. } => Some(*write_address),
        Request::Diagnostics { .. }
        | Request::ReportServerId
        | Request::ReadDeviceIdentification { .. } => None,
    }
}

/// FC 17 (§6.13): the server id, then the run indicator (always "on").
fn report_server_id(identity: &DeviceIdentity) -> Response {
    // FC, byte count and run indicator leave 250 bytes for the id.
    let room = MAX_PDU - 3;
    Response::ServerId {
        id: identity.server_id.iter().take(room).copied().collect(),
        running: true,
    }
}

/// Conformity level: regular identification, stream and individual access (§6.21).
const CONFORMITY: u8 = 0x82;
/// FC, MEI type, read code, conformity, more follows, next object id, object count.
const DEVICE_ID_HEADER: usize = 7;

/// FC 43/14 Read Device Identification (§6.21).
fn device_identification(identity: &DeviceIdentity, read_code: u8, object_id: u8) -> Response {
    let objects: [(u8, &str); 7] = [
        (0x00, &identity.vendor_name),
        (0x01, &identity.product_code),
        (0x02, &identity.revision),
        (0x03, &identity.vendor_url),
        (0x04, &identity.product_name),
        (0x05, &identity.model_name),
        (0x06, &identity.user_application_name),
    ];
    // Basic objects are mandatory, so always reported; regular ones only when set.
    let present = |(id, value): &(u8, &str)| *id <= 0x02 || !value.is_empty();
    // An object always fits a response on its own (§6.21); a longer value is cut.
    let value = |v: &str| -> Vec<u8> {
        v.as_bytes()
            .iter()
            .take(MAX_PDU - DEVICE_ID_HEADER - 2)
            .copied()
            .collect()
    };
    let response = |objects: Vec<(u8, Vec<u8>)>, more_follows: bool, next_object_id: u8| {
        Response::DeviceIdentification {
            read_code,
            conformity: CONFORMITY,
            more_follows,
            next_object_id,
            objects,
        }
    };
    if read_code == 4 {
        // Individual access: an object that does not exist is exception 02.
        return match objects.iter().find(|o| o.0 == object_id && present(o)) {
            Some((id, v)) => response(vec![(*id, value(v))], false, 0),
            None => Response::exception(fc::ENCAPSULATED_INTERFACE, Exception::IllegalDataAddress),
        };
    }
    // Stream access: basic 0x00–0x02, regular up to 0x7F, extended up to 0xFF (each includes
    // the ones before; this server has no extended objects).
    let last = match read_code {
        1 => 0x02,
        2 => 0x7F,
        _ => 0xFF,
    };
    let stream: Vec<(u8, &str)> = objects
        .iter()
        .filter(|o| o.0 <= last && present(o))
        .copied()
        .collect();
    // An object id that is not in the stream restarts it at object 0.
    let start = if stream.iter().any(|o| o.0 == object_id) {
        object_id
    } else {
        0
    };
    let mut size = DEVICE_ID_HEADER;
    let mut out = Vec::new();
    for (id, v) in stream.iter().filter(|o| o.0 >= start) {
        let v = value(v);
        if size + 2 + v.len() > MAX_PDU {
            // More follows: the client asks again from `id`.
            return response(out, true, *id);
        }
        size += 2 + v.len();
        out.push((*id, v));
    }
    response(out, false, 0)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn identity(long: usize) -> DeviceIdentity {
        DeviceIdentity {
            server_id: vec![1, 2],
            vendor_name: "mcemu".into(),
            product_code: "EMU".into(),
            revision: "0.1".into(),
            vendor_url: String::new(),
            product_name: "x".repeat(long),
            model_name: "y".repeat(long),
            user_application_name: String::new(),
        }
    }

    fn ids(r: &Response) -> (Vec<u8>, bool, u8) {
        match r {
            Response::DeviceIdentification {
                objects,
                more_follows,
                next_object_id,
                ..
            } => (
                objects.iter().map(|o| o.0).collect(),
                *more_follows,
                *next_object_id,
            ),
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn device_identification_streams_splits_and_refuses_unknown_objects() {
        let id = identity(10);
        assert_eq!(
            ids(&device_identification(&id, 1, 0)),
            (vec![0, 1, 2], false, 0)
        );
        // Empty regular objects (3, 6) are not reported.
        assert_eq!(
            ids(&device_identification(&id, 2, 0)),
            (vec![0, 1, 2, 4, 5], false, 0)
        );
        assert_eq!(
            ids(&device_identification(&id, 2, 4)),
            (vec![4, 5], false, 0)
        );
        assert_eq!(
            ids(&device_identification(&id, 1, 0x50)),
            (vec![0, 1, 2], false, 0),
            "unknown start restarts at 0"
        );
        assert_eq!(ids(&device_identification(&id, 4, 5)), (vec![5], false, 0));
        assert_eq!(
            device_identification(&id, 4, 3),
            Response::exception(0x2B, Exception::IllegalDataAddress)
        );
        assert_eq!(
            device_identification(&id, 4, 0x80),
            Response::exception(0x2B, Exception::IllegalDataAddress)
        );
        // Two 200-byte objects cannot share a response: more follows from object 5.
        let id = identity(200);
        let first = device_identification(&id, 2, 0);
        assert_eq!(ids(&first), (vec![0, 1, 2, 4], true, 5));
        let mut bytes = vec![];
        pdu::encode_response(&first, &mut bytes);
        assert!(bytes.len() <= MAX_PDU);
        assert_eq!(ids(&device_identification(&id, 2, 5)), (vec![5], false, 0));
        // A value longer than a PDU is cut to fit.
        let id = identity(400);
        let mut bytes = vec![];
        pdu::encode_response(&device_identification(&id, 4, 4), &mut bytes);
        assert_eq!(bytes.len(), MAX_PDU);
    }

    #[test]
    fn report_server_id_fits_a_pdu() {
        let mut id = identity(0);
        id.server_id = vec![7; 300];
        let mut bytes = vec![];
        pdu::encode_response(&report_server_id(&id), &mut bytes);
        assert_eq!(bytes.len(), MAX_PDU);
        assert_eq!(
            bytes[1] as usize,
            MAX_PDU - 2,
            "byte count: id + run indicator"
        );
        assert_eq!(bytes.last(), Some(&0xFF));
    }

    #[test]
    fn address_coverage() {
        let r = Request::ReadHoldingRegisters {
            address: 10,
            quantity: 5,
        };
        assert!(!covers(&r, 9) && covers(&r, 10) && covers(&r, 14) && !covers(&r, 15));
        let r = Request::ReadHoldingRegisters {
            address: 0xFFFF,
            quantity: 1,
        };
        assert!(covers(&r, 0xFFFF));
        let r = Request::ReadWriteMultipleRegisters {
            read_address: 0,
            read_quantity: 1,
            write_address: 100,
            write_quantity: 2,
            values: &[0, 0, 0, 0],
        };
        assert!(covers(&r, 0) && covers(&r, 101) && !covers(&r, 50));
    }
}
